// Attack: the solution by an absolute path, written through /proc/self/root (which is "/") so
// that a check comparing path prefixes without resolving links would miss it. The path is this
// machine's (the kit checked out at /work/hostile); where no kit is there, the #else branch
// names a file that does not exist and the file does not compile. Either way: no points.
#if __has_include("/proc/self/root/work/hostile/solutions/task1_two_masses/spring_damper.cpp")
#include "/proc/self/root/work/hostile/solutions/task1_two_masses/spring_damper.cpp"
#else
#include "/proc/self/root/springlab/solutions/task1_two_masses/spring_damper.cpp"
#endif
