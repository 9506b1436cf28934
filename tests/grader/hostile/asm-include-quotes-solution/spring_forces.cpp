// Attack: the assembler's .include reads the kit's solution as assembler source; every line of it
// is an error that the assembler quotes, and the grader would show the compiler's messages to the
// student. The path is relative to the grader's private copy (<work>/submissions/N-name/...).
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

using namespace springlab;

asm(".include \"../../../../../solutions/task2_four_masses/spring_forces.cpp\"");

void springlab::accumulate_spring_forces(const std::vector<Spring>&, const Vectors&,
                                         const Vectors&, Vectors&) {}
