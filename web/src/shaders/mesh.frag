// The relit radiance into the half-float HDR target, whose range ends at 65504: beyond it a
// value may turn inf, and blending inf (inf · 0) gives NaN, which tone-maps to black. Clamped
// there, a light of 1e20 still saturates to white after any exposure that shows it.
precision highp float;
in vec3 vRadiance;
out vec4 fragColour;
void main() { fragColour = vec4(min(vRadiance, vec3(65504.0)), 1.0); }
