#version 300 es
// The flame still, warped by the mesh. Beyond the paper: a bigger flame
// burns a little brighter and whiter, a smaller one dimmer and redder.
precision mediump float;

uniform sampler2D u_still;
in vec2 v_uv;
in float v_bright;
out vec4 o_color;

void main() {
  vec4 c = texture(u_still, v_uv);
  float b = clamp(v_bright, 0.0, 1.5);
  vec3 tint = mix(vec3(1.0, 0.78, 0.6), vec3(1.0, 1.0, 0.96), smoothstep(0.55, 1.15, b));
  vec3 rgb = min(c.rgb * tint * (0.8 + 0.2 * b), vec3(1.0));
  o_color = vec4(rgb * c.a, c.a);  // premultiplied
}
