#pragma once
// The OpenGL 3.3 core entry points, straight from the system libGL (Mesa exports every core
// function, so no loader is needed), and GLFW without its own GL header.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
