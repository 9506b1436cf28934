// Attack: the solution by an absolute path, written through /proc/self/root (which is "/") so
// that a check comparing path prefixes without resolving links would miss it. The batch writes
// the kit's folder in place of @KIT@.
#include "/proc/self/root@KIT@/solutions/task1_two_masses/spring_damper.cpp"
