// The one place that includes the GLES 3 headers.
#pragma once

#include <GLES3/gl3.h>
