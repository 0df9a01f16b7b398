#pragma once
// The OpenGL 4.5 core API. libglvnd's libOpenGL exports every core entry point, so with
// GL_GLEXT_PROTOTYPES (set by the build) no loader is needed on top of an EGL context.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
