#version 450 core
// Directional and spot shadow maps keep only the depth buffer.
void main() {}
