#version 300 es
// The Perlin fire's ray march (after the Perlin-fire paper). The unit volume
// is [-0.5, 0.5] x [0, 1] x [-0.5, 0.5]; the profile texture swept about y
// gives its shape. Each fragment marches from where its ray enters the box to
// the back face it was drawn for, in equal steps from a jittered start; at
// each step octaves of noise displace the profile lookup along y and the
// looked-up colour is summed. The ray stops at the volume's edge or at the
// obstacle (logs, grate) filling the box below u_obstacle.
// The program builder puts perlinfire_noise.frag in front of this text and
// defines PF_NOISE_KIND: 0 simplex3d, 1 flow3d, 2 simplex4d, 3 perlin4d, and
// PF_SHADING: 0 sums the profile's colours along the ray (the paper's way:
// soft, like glowing gas), 1 draws flame sheets: the profile's density, moved
// by the noise, is cut at a sharp threshold (so the noise tears the outline
// into tongues that split and detach), the hot path length through the sheets
// is exposed like a camera sees a flame (cores clip to white) and coloured
// by a black-body ramp (fire_ramp.glsl, applied here or after upscaling);
// PF_SWELL_POINTS is the number of the swell's heights across the fire;
// PF_TONGUE_COMB and PF_FINE_TONGUES are defined only for a fire that uses
// them (tongue_comb, fine_gap above 0): on a CPU renderer even a branch
// on a uniform that is never taken cost the Perlin fireplace 11% a frame.
precision highp float;
precision highp int;

in vec3 v_unit;
out vec4 o_color;

uniform vec3 u_camera;       // the camera in unit space
uniform vec3 u_box_min;      // the march box (the unit volume widened by the lean)
uniform vec3 u_box_max;
uniform vec3 u_world_scale;  // unit space -> lengths in fire heights
uniform vec3 u_noise_scale;  // unit space -> noise lattice (octave 0)
uniform float u_step_length;  // fire heights per step
uniform int u_max_steps;
uniform vec4 u_bound;        // x - y*h: radius (unit) bounding the profile at height h; z: top
uniform int u_octaves;
uniform float u_weights[8];
uniform vec3 u_offset[8];    // per octave: drift and rise, wrapped where the noise repeats
uniform vec2 u_flow_cs[8];   // per octave: cos, sin of the flow angle
uniform float u_time4[8];    // per octave: the 4th coordinate
uniform vec2 u_lean;         // where the flame's tip is pushed (x, z), unit space
uniform float u_displacement;
uniform float u_turbulence_mean;  // subtracted, so displacement does not shorten the flame
uniform float u_intensity;
uniform float u_obstacle;    // the box is solid below this height (unit y)
uniform float u_obstacle_relief;  // how far its top rises and falls across the fire (unit y)
uniform vec3 u_color;
uniform sampler2D u_profile; // premultiplied RGBA; u = radius, v = 1 - height
uniform vec2 u_sheet;        // flame shading: density threshold, the density range above it to full
uniform float u_rise_growth; // displacement at the base, relative to the top's
uniform float u_wobble;      // how much the noise also moves the lookup radius
uniform int u_ramp_here;     // 1: colour here; 0: write the exposure for the composite
uniform int u_slices;        // flame shading: camera-facing slabs sampled
uniform vec3 u_tongue_scale;  // flame shading: unit space -> the tongue field's lattice (x, y); z: a comb's wander (0: creases)
uniform vec3 u_tongue_offset; // its drift, rise and evolution, wrapped where the noise repeats
uniform float u_tongue_roots; // how deep the gaps cut at the very base (separate roots)
uniform float u_glow;        // flame shading: brightness of the glow around the flames
uniform float u_cooling;     // flame shading: share of the heat lost from the bed's top to the tips
uniform float u_trail_lift;  // a shutter's trail: what its fade takes off (1/255) over this frame's share
uniform float u_swell;       // flame shading: how far the flames' height swells and sinks across the fire
uniform float u_swell_scale[PF_SWELL_POINTS];  // the lookup's height scale at points across the fire (perlinfire.cpp)
uniform vec3 u_fine_scale;   // flame shading: the fine tongue field's lattice (x, y; z 0: creases)
uniform vec3 u_fine_offset;  // its drift, rise and evolution (with the turbulence's)
uniform vec2 u_fine_gap;     // x: how deep its gaps cut, of the broad gaps' depth (0: none); y: their width
uniform vec3 u_tongue_gap;    // x: how deep gaps between tongues cut (0: none); y: their width;
                              // z: the height above the base where they reach full depth

float pf_turbulence(vec3 q) {
  vec3 b = q * u_noise_scale;
  float sum = 0.0;
  float f = 1.0;
  for (int o = 0; o < 8; ++o) {
    if (o >= u_octaves) break;
    vec3 p = b * f - u_offset[o];
#if PF_NOISE_KIND == 0
    float n = pf_snoise3(p);
#elif PF_NOISE_KIND == 1
    float n = pf_snoise3_flow(p, u_flow_cs[o]);
#elif PF_NOISE_KIND == 2
    float n = pf_snoise4(vec4(p, u_time4[o]));
#else
    float n = pf_pnoise4(vec4(p, u_time4[o]));
#endif
    sum += u_weights[o] * abs(n);
    f *= 2.0;
  }
  return sum;
}

// A tongue field's |value| at q (unit space): 0 in the gaps between tongues.
// scale: unit space -> its lattice (x, y), z: 0 for the noise's creases, or
// a comb's wander (one gap per cell across, wandering along the noise by up
// to that share of the spacing, so the gaps' share of the fire stays steady).
float pf_tongue_field(vec3 q, vec3 scale, vec3 offset) {
#ifdef PF_TONGUE_COMB
  if (scale.z > 0.0) {
    float warp = pf_snoise3(vec3(q.x * 0.5, q.y, 0.0) * vec3(scale.xy, 0.0) -
                            offset * vec3(0.5, 1.0, 1.0));
    return abs(sin(3.14159265 * (q.x * scale.x - offset.x + scale.z * warp)));
  }
#endif
  return abs(pf_snoise3(vec3(q.x, q.y, 0.0) * vec3(scale.xy, 0.0) - offset));
}

void main() {
  vec3 d = v_unit - u_camera;  // t = 1 is the back face
  // Where the ray enters the box (slab test); 0 when the camera is inside.
  vec3 inv = 1.0 / mix(d, vec3(1e-7), lessThan(abs(d), vec3(1e-7)));
  vec3 tn = min((u_box_min - u_camera) * inv, (u_box_max - u_camera) * inv);
  float t_in = max(max(max(tn.x, tn.y), tn.z), 0.0);
  float t_out = 1.0;
  // The obstacle: a ray entering below its top is blocked at once; one going
  // down stops where it meets the top.
  if (u_camera.y + d.y * t_in < u_obstacle) discard;
  if (d.y < 0.0) t_out = min(t_out, (u_obstacle - u_camera.y) / d.y);
  // Nothing is drawn above u_bound.z (the profile's highest non-empty row;
  // sheets: a quarter of the volume higher, where tongues that rise past the
  // profile have faded out), nor outside the cone that bounds the profile,
  // widened and shifted by the lean: march only the part of the ray inside.
  if (d.y > 0.0) t_out = min(t_out, (u_bound.z - u_camera.y) / d.y);
  else if (u_camera.y + d.y * t_in > u_bound.z) t_in = max(t_in, (u_bound.z - u_camera.y) / d.y);
  vec2 cxz = u_camera.xz - 0.5 * u_lean;
  float a = u_bound.x - u_bound.y * u_camera.y;  // cone radius at the camera's height
  float qa = dot(d.xz, d.xz) - u_bound.y * u_bound.y * d.y * d.y;
  float qb = 2.0 * (dot(cxz, d.xz) + a * u_bound.y * d.y);
  float qc = dot(cxz, cxz) - a * a;
  if (qa > 1e-9) {
    float disc = qb * qb - 4.0 * qa * qc;
    if (disc <= 0.0) discard;
    float h = sqrt(disc);
    t_in = max(t_in, (-qb - h) / (2.0 * qa));
    t_out = min(t_out, (-qb + h) / (2.0 * qa));
  }
  if (t_out <= t_in) discard;

#if PF_SHADING == 0
  // Equal steps of about u_step_length fire heights, from a jittered start
  // (the permutation texture again) so that steps do not band.
  float len = length(d * u_world_scale) * (t_out - t_in);
  int n = clamp(int(ceil(len / u_step_length)), 1, u_max_steps);
  float dt = (t_out - t_in) / float(n);
  float ds = len / float(n);
  float jitter = (float(pf_perm2(int(gl_FragCoord.x), int(gl_FragCoord.y))) + 0.5) / 256.0;
  vec4 acc = vec4(0.0);
  for (int k = 0; k < 512; ++k) {
    if (k >= n) break;
    vec3 p = u_camera + d * (t_in + (float(k) + jitter) * dt);
    // Wind bends the flame: the lookup slides sideways, more towards the top.
    vec3 q = p;
    q.xz -= u_lean * (p.y * p.y);
    float r = 2.0 * length(q.xz);
    if (r >= 1.0) continue;  // outside the swept profile: nothing to add
    float v = p.y + u_displacement * (pf_turbulence(q) - u_turbulence_mean);
    acc += textureLod(u_profile, vec2(r, 1.0 - v), 0.0) * ds;
  }
#else
  // Flame sheets: the volume is cut into u_slices slabs facing the camera
  // (after Horvath & Geiger: 2-D detail is what reads as fire on a flat
  // screen), each sampled once where the ray crosses its middle. No jitter:
  // each slab's field is continuous across the screen, so its edges stay
  // crisp instead of breaking into speckle.
  vec2 facing = dot(u_camera.xz, u_camera.xz) > 1e-6 ? normalize(u_camera.xz) : vec2(0.0, 1.0);
  float along = dot(d.xz, facing);
  float hot = 0.0;
  float glow = 0.0;  // path length through the flames' dim envelope (density below the sheets')
  if (abs(along) > 1e-5) {
    // Path length through one slab, in fire heights (capped for grazing rays).
    float slab = (u_world_scale.x + u_world_scale.z) * 0.5 / float(u_slices);
    float ds = slab * min(length(d * u_world_scale) / abs(along * (u_world_scale.x + u_world_scale.z) * 0.5), 4.0);
    float c0 = dot(u_camera.xz, facing);
    for (int k = 0; k < 16; ++k) {
      if (k >= u_slices) break;
      float plane = (float(k) + 0.5) / float(u_slices) - 0.5;
      float t = (plane - c0) / along;
      if (t < t_in || t > t_out) continue;
      vec3 p = u_camera + d * t;
      vec3 q = p;
      q.xz -= u_lean * (p.y * p.y);
      float r = 2.0 * length(q.xz);
      if (r >= 1.0) continue;
      // Turbulence tears the upper flame more than its base; where it lifts
      // the lookup it also widens it, so gaps between tongues open deep.
      float turb = pf_turbulence(q) - u_turbulence_mean;
      float h = p.y;
      if (u_swell > 0.0) {
        // A real fire is tall where its fuel burns hardest and low elsewhere,
        // and that changes over seconds; a row of tongues all as tall reads as
        // a picket fence. The lookup's height above the base is scaled by
        // slow random heights at PF_SWELL_POINTS across the fire, joined smoothly
        // (their mean kept, so the lit area stays: perlinfire.cpp).
        float base = max(u_obstacle, 0.0);
        float across = clamp(q.x + 0.5, 0.0, 1.0) * float(PF_SWELL_POINTS - 1);
        int i = min(int(across), PF_SWELL_POINTS - 2);
        float scale = mix(u_swell_scale[i], u_swell_scale[i + 1], smoothstep(0.0, 1.0, across - float(i)));
        h = base + (p.y - base) * scale;
      }
      float v = h + u_displacement * turb * mix(u_rise_growth, 1.0, clamp(p.y, 0.0, 1.0));
      vec4 c = textureLod(u_profile, vec2(r * (1.0 + u_wobble * turb), 1.0 - v), 0.0);
      // Tongues that rise past the profile fade out below the bound's top.
      float density = c.a * (1.0 - smoothstep(u_bound.z - 0.2, u_bound.z, p.y));
      // Flames rise from between the logs: each slab fades in above the
      // obstacle over a ragged band, else its cut along the logs' top shows
      // as one straight bright line per slab (seen from above, a stack of
      // them outlines the volume's floor).
      // Its top rises and falls across the fire (u_obstacle_relief; static, as
      // the tops of a pile of logs), so the feet do not stand on one line.
      // The relief's noise (in -1..1) only where it can move the fade: a sample
      // above the highest foot's band is faded by nothing either way.
      if (u_obstacle > 0.0) {
        float y = p.y + 0.05 * turb;
        float foot = u_obstacle;
        if (u_obstacle_relief > 0.0 && y < u_obstacle + u_obstacle_relief + 0.05)
          foot += u_obstacle_relief * pf_snoise3(vec3(q.x * 3.0, 17.3, 0.5));
        density *= smoothstep(foot, foot + 0.05, y);
      }
      // The gaps only ever thin the density (depth <= 1), so where it is
      // already below the sheets' edge they cannot change this sample: skip
      // their noise there (most of the box: the air between the tongues).
      if (u_tongue_gap.x > 0.0 && density > u_sheet.x) {
        // Gaps between tongues: the creases (|n| near 0) of one tall noise
        // field, the same through the whole depth, so the slabs do not fill
        // them in; they open from the base upwards and rise with the fire. The
        // field evolves by moving through its third axis (no spin: spinning
        // all cells at once would make the whole fire pulse in step).
        float n = pf_tongue_field(q, u_tongue_scale, u_tongue_offset);
        float base = max(u_obstacle, 0.0);
        float depth = u_tongue_gap.x *
                      mix(u_tongue_roots, 1.0, smoothstep(base, base + u_tongue_gap.z, p.y));
        // Gaps widen upwards, so tongues taper to their tips.
        float widen = mix(0.6, 1.4, clamp(p.y, 0.0, 1.0));
        float w = u_tongue_gap.y * widen;
        density *= 1.0 - depth * (1.0 - smoothstep(0.4 * w, w, n));
#ifdef PF_FINE_TONGUES
        {
          float m = pf_tongue_field(q, u_fine_scale, u_fine_offset);
          float wf = u_fine_gap.y * widen;
          density *= 1.0 - u_fine_gap.x * depth * (1.0 - smoothstep(0.4 * wf, wf, m));
        }
#endif
      }
      float sheet = clamp((density - u_sheet.x) / u_sheet.y, 0.0, 1.0);
      // Heat: the profile's straight colour (its luminance), hotter at the base.
      float heat = dot(c.rgb, vec3(0.299, 0.587, 0.114)) / max(c.a, 1.0 / 255.0);
      // The gas cools as it rises: what the noise lifts high (tips, pieces
      // that broke off) glows orange and dim, not white like the bed. The
      // lookup's own heat cannot say so, as the noise moved it.
      heat *= 1.0 - u_cooling * smoothstep(u_bound.z * 0.3, u_bound.z, p.y);
      hot += sheet * heat * ds;
      glow += smoothstep(0.0, u_sheet.x, c.a) * ds;
    }
  }
#endif
#if PF_SHADING == 0
  acc *= u_intensity;
  o_color = vec4(acc.rgb * u_color, 1.0 - exp(-acc.a));
#else
  float exposure = 1.0 - exp(-u_intensity * hot);
  // The glow: the hot air and lit smoke around the flames, dim and soft.
  float g = u_glow * (1.0 - exp(-6.0 * glow));
  o_color = u_ramp_here == 1 ? fire_ramp(exposure, g, u_color) : vec4(exposure, g, 0.0, 0.0);
#endif
  // With a shutter the fade takes 1/255 off the trail each frame, so that it
  // ends at zero; this frame's share (1 - keep) of the lift gives it back
  // wherever the fire is drawn, so a still flame keeps its level.
  o_color += vec4(u_trail_lift);
}
