// For code compiled into an implementation build (the tests): the Implementation table of the
// build this translation unit belongs to, so a test written once runs against every build.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/task_api.hpp"

SPRINGLAB_TASK_API_BEGIN

const Implementation& implementation();

SPRINGLAB_TASK_API_END
