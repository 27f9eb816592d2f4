in vec3 vRadiance;
out vec4 fragColour;
void main() { fragColour = vec4(vRadiance, 1.0); }
