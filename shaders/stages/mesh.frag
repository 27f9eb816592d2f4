// Every mesh pass's fragments: the interpolated exit radiance, into the linear HDR target.
in vec3 vRadiance;
out vec4 fragColour;
void main() { fragColour = vec4(vRadiance, 1.0); }
