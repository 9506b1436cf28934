// The helper header of the "own-header" case: it belongs to the submission and sits next to
// spring_damper.cpp.
#pragma once

/// Hooke's signed force along the spring: -k times the stretch.
inline double hooke(double k, double stretch) { return -k * stretch; }
