#version 300 es
// A burning log, every frame: its static look from the hearth's cache
// (hearth_log.frag, read at this pixel), lit by the fire's flickering light
// (u_light: colour * flicker, w: ember strength), its cracks glowing and
// pulsing each at its own pace, irregularly (value_noise.frag's ember_pulse,
// put before this).
precision highp float;

in vec3 v_world;
in vec3 v_normal;
out vec4 o_color;

uniform vec3 u_light_pos;
uniform vec4 u_light;
uniform float u_time;
uniform sampler2D u_colour;  // the cache: unlit colour
uniform sampler2D u_crack;   // crack glow (hi, lo), pulse hashes
uniform sampler2D u_normal;  // the normal with the bark's relief (0.5 + 0.5 n)
uniform ivec2 u_origin;      // the viewport's origin (the cache starts there)
uniform vec3 u_camera;       // world space

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  vec3 colour = texelFetch(u_colour, p, 0).rgb;
  vec4 k = texelFetch(u_crack, p, 0);
  // The light falls on the relief (n); the log's outline and its underside
  // on the coals follow its round form.
  vec3 form = normalize(v_normal);
  vec3 n = normalize(texelFetch(u_normal, p, 0).xyz * 2.0 - 1.0);
  vec3 to_light = u_light_pos - v_world;
  float d2 = dot(to_light, to_light);
  float toward = dot(n, normalize(to_light));  // 1 facing the fire, -1 turned away
  float facing = max(toward, 0.0);
  // What faces the fire, and the tops the flames lick, flicker bright. The
  // fire is no point: it is as wide as the bed and its flames rise in front
  // of the logs too, so light wraps round a log (a front log's face is dim,
  // not black). The firebox and the other logs glow back a paler light, as a
  // camera sees it: real logs by a fire read brown (R:G:B about 1.7:1:0.6),
  // not the fire's own orange.
  float wrap = max(toward + 0.7, 0.0) / 1.7;
  // Both fall off towards the bed's ends, away from the flames.
  float near = 1.0 / (1.0 + d2 * 5.0);
  vec3 lit = u_light.rgb * (0.05 + 3.0 * facing * facing + 0.3 * wrap * wrap + 0.8 * max(n.y, 0.0)) * near;
  // The paler fill comes from above (the lit firebox and the flames over the
  // bed), so a log's face darkens from its top down to its underside, and
  // towards its outline, where the surface turns away from the camera: the
  // shading that makes it read round, not a flat plank.
  float from_above = smoothstep(-0.7, 0.8, n.y);
  float turned = max(dot(form, normalize(u_camera - v_world)), 0.0);
  lit += dot(u_light.rgb, vec3(0.4, 0.4, 0.2)) * vec3(1.0, 0.92, 0.86) *
         (0.035 + 0.4 * from_above) * (0.35 + 0.65 * turned) * near;
  // The coals under the logs light their undersides and lower flanks.
  lit += u_light.rgb * vec3(1.0, 0.6, 0.35) * (0.55 * u_light.w * max(-n.y + 0.3, 0.0));
  // Where a log lies on the coals its char is red hot: a soft glow that
  // climbs its lower flank, breathing with the fire's light.
  float underside = smoothstep(0.1, -0.7, form.y);
  vec3 hot = vec3(1.0, 0.28, 0.04) * underside * underside * 0.5 * u_light.w *
             (0.7 + 0.3 * sin(u_time * 0.9 + v_world.x * 7.0));
  float crack = k.x + k.y * (1.0 / 255.0);
  float pulse = crack > 0.0 ? 0.2 + 0.8 * ember_pulse(u_time, 0.4 + 0.6 * k.z, k.w) : 0.0;
  float glow = crack * pulse * u_light.w;
  vec3 ember = vec3(1.0, 0.32, 0.05) * glow * 1.6 + vec3(1.0, 0.7, 0.3) * (glow * glow * glow) * 0.6;
  // Backlit by the flames, a log's outline on the fire's side catches a
  // little of their light along its top edge (char and ash have a dull
  // sheen, so it does not take the surface's colour). Faint: in footage a
  // front log is dark, and a bright rim (4x this) joined the logs and the
  // flames into one solid lit mass (c2st.py: the eigen fireplace's d' 5.9
  // went to 6.5, beyond the real fires).
  float away = 1.0 - turned;
  float rim = away * away * away * smoothstep(-0.1, 0.7, toward);
  vec3 sheen = u_light.rgb * vec3(1.0, 0.72, 0.48) * rim * near;
  o_color = vec4(colour * (lit + vec3(0.03)) + ember + hot * (0.3 + colour) + sheen, 1.0);
}
