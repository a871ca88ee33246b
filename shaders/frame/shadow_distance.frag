#version 450 core
// Cube shadow maps store the distance to the light, so every face compares the same quantity.
in vec3 vPosition;
uniform vec3 uLightPosition;
layout(location = 0) out float outDistance;
void main() { outDistance = length(vPosition - uLightPosition); }
