#version 330 core
// Lines and translucent fills: per-vertex colour, no lighting. In the 3-D views every point is
// moved a fraction depth_bias of the way towards the camera: along its own ray, so it lands on the
// same pixel, but in front of the surface's faces that would otherwise hide part of a wide line.
layout(location = 0) in vec3 position;
layout(location = 1) in vec4 color;
uniform mat4 view_projection;
uniform vec3 eye;
uniform float depth_bias;
out vec4 v_color;
void main() {
  v_color = color;
  gl_Position = view_projection * vec4(mix(position, eye, depth_bias), 1.0);
}
