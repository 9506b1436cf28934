// Attack on the compiler, not the tests: #include "/dev/zero" never ends -- the compiler reads
// zeros until it runs out of memory (4 GB) or time (120 s). The grader must stop it and report
// that task 1 does not compile; every other task is graded as usual.
#include "/dev/zero"
