#version 330 core
// Lambert shading with an ambient floor; the light comes from the camera's side.
in vec3 v_normal;
uniform vec4 color;
uniform vec3 light_direction;
uniform float ambient;
out vec4 fragment;
void main() {
  float diffuse = abs(dot(normalize(v_normal), light_direction));  // two-sided: both faces of the sheet
  fragment = vec4(color.rgb * (ambient + (1.0 - ambient) * diffuse), color.a);
}
