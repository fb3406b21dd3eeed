#version 450
#extension GL_GOOGLE_include_directive : require
#define VKSKY_COMPOSITE 1
#include "tonemap_common.glsl"
