#version 300 es
// The Perlin fire's box: 36 vertices made from gl_VertexID (no vertex
// buffer), corners of the march box in the fire's unit space. The element
// draws only back faces, so each covered pixel gets exactly one fragment,
// also when the camera is inside the box; the fragment marches back from it.
precision highp float;

uniform mat4 u_model_view_projection;  // unit space -> clip space
uniform vec3 u_box_min;                 // the march box, unit space
uniform vec3 u_box_max;
out vec3 v_unit;

// Corner c = x + 2y + 4z; faces wound counter-clockwise seen from outside.
const int kCorner[36] = int[36](0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7,
                                3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6);

void main() {
  int c = kCorner[gl_VertexID];
  vec3 k = vec3(float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1));
  v_unit = mix(u_box_min, u_box_max, k);
  gl_Position = u_model_view_projection * vec4(v_unit, 1.0);
}
