// Attack: the whole file is an #include of the kit's own solution, by a path relative to this
// file as it sits in the kit's tasks/ folder. The grader compiles a private copy elsewhere, so
// the path must not reach the solution (does not compile), and if it did the include check must
// refuse it: task 1 gets nothing.
#include "../../solutions/task1_two_masses/spring_damper.cpp"
