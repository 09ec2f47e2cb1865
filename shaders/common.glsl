// Constants and small helpers shared by every shader.
const float PI = 3.14159265358979323846;

float saturate(float x) { return clamp(x, 0.0, 1.0); }
float clamped_dot(vec3 a, vec3 b) { return clamp(dot(a, b), 0.0, 1.0); }
