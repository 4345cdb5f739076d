#version 330 core
// The surface: Lambert shading per vertex (Gouraud), two-sided, with an ambient floor; the light
// comes from the camera's side. Per-vertex lighting keeps the fragment work at one interpolation.
// The curvature layer (tint_mix = 1) colours each vertex by its K instead of the surface's colour.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 tint;
uniform mat4 view_projection;
uniform vec4 color;
uniform vec3 light_direction;
uniform float ambient;
uniform float tint_mix;
out vec4 v_color;
void main() {
  float diffuse = abs(dot(normal, light_direction));
  vec3 base = mix(color.rgb, tint, tint_mix);
  v_color = vec4(base * (ambient + (1.0 - ambient) * diffuse), color.a);
  gl_Position = view_projection * vec4(position, 1.0);
}
