#version 330 core
// Anti-aliased lines without multisampling: each segment (a, b) is one instance, drawn as a quad
// in screen space reaching half_width + 0.5 px either side of the segment and half_width beyond its
// ends (so that the segments of a polyline overlap at their joints); line.frag fades the last
// pixel out, so the edge is blended with what is below instead of stair-stepped. Depth and the
// bias towards the camera are flat.vert's.
layout(location = 0) in vec3 a;
layout(location = 1) in vec4 color_a;
layout(location = 2) in vec3 b;
layout(location = 3) in vec4 color_b;
uniform mat4 view_projection;
uniform vec3 eye;
uniform float depth_bias;
uniform vec2 viewport;     // [pixels]
uniform float half_width;  // [pixels]
out vec4 v_color;
noperspective out float v_across;  // [pixels] from the segment's centre line
void main() {
  vec4 ca = view_projection * vec4(mix(a, eye, depth_bias), 1.0);
  vec4 cb = view_projection * vec4(mix(b, eye, depth_bias), 1.0);
  v_color = gl_VertexID >= 2 ? color_b : color_a;
  if (ca.w <= 0.0 || cb.w <= 0.0) {  // behind the camera: not drawn
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    v_across = 0.0;
    return;
  }
  vec2 half_viewport = 0.5 * viewport;
  vec2 sa = ca.xy / ca.w * half_viewport, sb = cb.xy / cb.w * half_viewport;  // [pixels]
  vec2 along = sb - sa;
  float len = length(along);
  along = len > 1e-6 ? along / len : vec2(1.0, 0.0);
  vec2 across = vec2(-along.y, along.x);
  bool at_b = gl_VertexID >= 2;
  float side = (gl_VertexID & 1) == 0 ? -1.0 : 1.0;
  float reach = half_width + 0.5;  // where line.frag's coverage reaches 0
  vec4 c = at_b ? cb : ca;
  vec2 s = (at_b ? sb : sa) + across * (side * reach) + along * (at_b ? half_width : -half_width);
  gl_Position = vec4(s / half_viewport * c.w, c.z, c.w);
  v_across = side * reach;
}
