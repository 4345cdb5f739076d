#version 330 core
// The surface: positions in world units, normals for Lambert shading.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 view_projection;
out vec3 v_normal;
void main() {
  v_normal = normal;
  gl_Position = view_projection * vec4(position, 1.0);
}
