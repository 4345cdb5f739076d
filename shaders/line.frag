#version 330 core
// Coverage of a pixel by a line half_width either side of its centre: 1 inside, falling to 0 over
// the pixel that the edge crosses.
uniform float half_width;  // [pixels]
in vec4 v_color;
noperspective in float v_across;
out vec4 fragment;
void main() {
  float coverage = clamp(half_width + 0.5 - abs(v_across), 0.0, 1.0);
  fragment = vec4(v_color.rgb, v_color.a * coverage);
}
