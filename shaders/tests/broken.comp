#version 450 core
// Deliberately invalid: the test checks the compile error names this file.
layout(local_size_x = 1) in;
void main() { undefined_function(); }
