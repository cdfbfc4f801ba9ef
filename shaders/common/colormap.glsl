// The view's own colour map (grey-inverted, hot-iron, pet, ...) for projections and MPR, a
// compile-time variant (MVW_IMAGE_COLORMAP) so the grey default runs exactly as before. The
// 256 entries are looked up by the 8-bit grey the image would otherwise show, so a pixel is
// exactly palette[grey byte] (the readback rounds grey * 255 the same way).
#ifndef MVW_COMMON_COLORMAP
#define MVW_COMMON_COLORMAP

uniform sampler1D uImageColormap;  // 256 x RGBA8, nearest

vec3 imageColour(float grey) {
#if defined(MVW_IMAGE_COLORMAP)
  int index = int(floor(clamp(grey, 0.0, 1.0) * 255.0 + 0.5));
  return texelFetch(uImageColormap, index, 0).rgb;
#else
  return vec3(grey);
#endif
}

// What a ray that meets nothing shows: the background, through the colour map as the grey it
// is (black becomes the map's lowest colour: white for grey-inverted, as a reader expects).
vec3 backgroundColour(vec3 background) {
#if defined(MVW_IMAGE_COLORMAP)
  return imageColour(dot(background, vec3(1.0 / 3.0)));
#else
  return background;
#endif
}

#endif
