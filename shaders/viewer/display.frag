// The texel as stored: the image was converted to 8-bit sRGB on the CPU by the same code
// that writes the run's PNGs, so a screenshot can be compared with them byte for byte.
layout(binding = 0) uniform sampler2D image;
in vec2 v_uv;
layout(location = 0) out vec4 out_colour;
void main() { out_colour = vec4(texture(image, v_uv).rgb, 1.0); }
