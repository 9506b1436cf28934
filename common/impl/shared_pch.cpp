// No code: the target this file belongs to only makes the precompiled header that the reference's
// objects share (springlab_share_solutions_pch in common/implementations.cmake).
