#version 330 core
in vec4 v_color;
out vec4 fragment;
void main() { fragment = v_color; }
