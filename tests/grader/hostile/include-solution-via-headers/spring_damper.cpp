// Attack: the solution reached through the kit's header folder, which submission code may use:
// <springlab/../../../solutions/...> starts in common/include, so it names the kit's solution
// wherever the kit is. The grader's include check must see through the ".." and refuse it.
#include <springlab/../../../solutions/task1_two_masses/spring_damper.cpp>
