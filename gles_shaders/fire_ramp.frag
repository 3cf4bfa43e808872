#version 300 es
// The flame's colour from its exposure e (0..1: 1 - exp(-k * hot path
// length)), as a camera sees wood fire (../shared/data/flames/*/frames_rgb):
// deep orange where the sheets are thin, yellow-orange, then cores clipped
// to near white. Premultiplied, alpha = coverage. Shared by perlinfire.frag
// and perlinfire_composite.frag (the program builder puts it after the noise
// library); the composite colours after upscaling, so edges stay crisp at a
// reduced render scale.
// g (0..1) is a dim glow (hot air, lit smoke) that shows where the flame does not cover.
vec4 fire_ramp(float e, float g, vec3 tint) {
  vec3 c = vec3(0.9, 0.26, 0.03);
  c = mix(c, vec3(1.0, 0.6, 0.16), smoothstep(0.15, 0.4, e));
  c = mix(c, vec3(1.0, 0.84, 0.45), smoothstep(0.38, 0.62, e));
  c = mix(c, vec3(1.0, 0.97, 0.88), smoothstep(0.6, 0.88, e));
  float a = smoothstep(0.0, 0.42, e);
  vec3 glow = vec3(0.9, 0.3, 0.06) * g * (1.0 - a);
  return vec4(min(c * tint, vec3(1.0)) * a + glow * tint, a + (1.0 - a) * g);
}
