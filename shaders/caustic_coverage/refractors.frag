#version 450 core
// Depth only (caustic_coverage.c).
void main() {}
