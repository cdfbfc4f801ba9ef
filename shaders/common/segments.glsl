// Segment outlines (MPR): one bit per segment in an integer texture on the segmentation's own
// grid, read at the nearest voxel. A pixel lies on a segment's outline when it is inside the
// segment and one of its four screen neighbours (world +- dFdx, dFdy) is not; it takes the
// colour of the lowest-numbered segment whose outline it is on.
uniform usampler3D uSegments;
uniform mat4 uSegmentsFromWorld;  // anatomical world (LPS mm) -> segmentation voxel index
uniform ivec3 uSegmentDims;
uniform int uSegmentCount;        // 0: no outlines
uniform vec3 uSegmentColours[16];

uint segmentBits(vec3 world) {
  ivec3 i = ivec3(floor((uSegmentsFromWorld * vec4(world, 1.0)).xyz + 0.5));
  if (any(lessThan(i, ivec3(0))) || any(greaterThanEqual(i, uSegmentDims))) return 0u;
  return texelFetch(uSegments, i, 0).r;
}

// dx, dy: the world step to the next pixel right and up (dFdx, dFdy of the world position,
// taken where control flow is still uniform).
vec3 outlineSegments(vec3 rgb, vec3 world, vec3 dx, vec3 dy) {
  if (uSegmentCount == 0) return rgb;
  uint centre = segmentBits(world);
  if (centre == 0u) return rgb;
  uint all4 = segmentBits(world + dx) & segmentBits(world - dx) & segmentBits(world + dy) &
              segmentBits(world - dy);
  uint edge = centre & ~all4;
  for (int s = 0; s < uSegmentCount; ++s)
    if ((edge & (1u << uint(s))) != 0u) return uSegmentColours[s];
  return rgb;
}
