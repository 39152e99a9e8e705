// The IBFVS pass's main() (also the deferred pass's second half): F_t at
// t(x) blended with the noise (equations 10-12), and F.
#ifdef IBFVS_CUBIC
// Catmull-Rom interpolation of F_t at uv from five bilinear taps: per axis the
// two middle weights are merged into one bilinear tap between their texels,
// and of the 3 x 3 taps that leaves, the four corners (weights w0 w3 and the
// like: at most 1/64 together) are dropped and the rest renormalised, which
// changes no measure of the picture and saves four of llvmpipe's costliest
// reads. Each frame's bilinear resampling blurs F_t by up to a quarter of a
// pixel squared across the flow, and over 1 / alpha frames that adds up; the
// cubic keeps the grain fine. Where a tap has background in its footprint,
// the bilinear value is kept (no inflow through the wider footprint).
vec4 sample_cubic(vec2 uv, vec4 bilinear) {
  vec2 size = vec2(textureSize(u_previous, 0));
  vec2 p = uv * size - 0.5;
  vec2 base = floor(p);
  vec2 f = p - base;
  vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
  vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
  vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
  vec2 w3 = f * f * (-0.5 + 0.5 * f);
  vec2 w12 = w1 + w2;
  vec2 t0 = (base - 0.5) / size, t12 = (base + 0.5 + w2 / w12) / size, t3 = (base + 2.5) / size;
  vec2 tx[3] = vec2[3](t0, t12, t3), wx[3] = vec2[3](w0, w12, w3);
  vec4 sum = vec4(0.0);
  float lowest = 1e30, weights = 0.0;
  const ivec2 taps[5] = ivec2[5](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1), ivec2(2, 1), ivec2(1, 2));
  for (int k = 0; k < 5; ++k) {
    ivec2 ij = taps[k];
    vec4 t = textureLod(u_previous, vec2(tx[ij.x].x, tx[ij.y].y), 0.0);
    lowest = min(lowest, stored_depth(t));
    float w = wx[ij.x].x * wx[ij.y].y;
    sum += w * t;
    weights += w;
  }
  sum /= weights;
#ifdef IBFVS_MONO_TEXTURE
  return lowest > -255.0 ? vec4(clamp(sum.r, 0.0, 1.0), bilinear.g, 0.0, 0.0) : bilinear;
#else
  return lowest > -255.0 ? vec4(clamp(sum.rgb, 0.0, 1.0), bilinear.a) : bilinear;
#endif
}
#endif

void main() {
  Here here = surface_here();
  // A point that was behind the eye has no image position: no advection there.
  bool ahead = here.ahead;
  vec2 unshifted = here.unshifted;
  vec2 texcoord = unshifted - u_texture_shift * u_inverse_size;
  vec4 stored = textureLod(u_previous, texcoord, 0.0);
#ifdef IBFVS_CUBIC
  stored = sample_cubic(texcoord, stored);
#endif
  vec3 previous = stored_value(stored);
  float previous_depth = stored_depth(stored);
#ifdef IBFVS_OBJECT_NOISE
  float g = solid_noise(v_position_object);
#else
  float g = noise(gl_FragCoord.xy - u_noise_shift);
#endif
  // Section 3.5 without the inflow: where t(x) = T(r - v dt) lands outside
  // the last frame's surface (the background holds kNoDepth, so one
  // background texel in the bilinear footprint is enough), outside the
  // image, or on a surface at another depth (an occlusion edge), the image
  // holds nothing of this surface: start from fresh noise instead. The
  // tolerance covers the step off the surface (a few pixels: well under 2%
  // of the depth), the depth's change across a pixel and 16-bit storage. While the image is dragged (3.7) only
  // coverage counts: a depth below -255 has a background texel in its
  // footprint (bilinear weights come in steps of 1/256 at the least).
  float depth = here.depth;
  float from_depth = here.from_depth;
  float tolerance = 0.02 * abs(from_depth) + 2.0 * here.depth_width;
  bool inside = all(greaterThanEqual(texcoord, vec2(0.0))) && all(lessThanEqual(texcoord, vec2(1.0)));
  bool dragged = u_texture_shift != vec2(0.0);
  bool same_surface = ahead && inside &&
                      (dragged ? previous_depth > -255.0
                               : abs(previous_depth - from_depth) <= tolerance ||
                                     previous_depth >= 65000.0);  // kAnyDepth: put in from outside
  vec2 moved = ahead && u_locked == 0 ? gl_FragCoord.xy - unshifted / u_inverse_size : vec2(0.0);
  float moved_length = length(moved);
  // The streaks' direction: the flow's displacement alone (a jump of the
  // surface or the camera's turn is not along them), else this pixel's.
  vec2 flow = ahead && u_locked == 0 ? here.flow : vec2(0.0);
  float flow_length = length(flow);
  vec2 along = flow_length > 1e-6 ? flow / flow_length
             : moved_length > 1e-6 ? moved / moved_length : vec2(0.0);
  vec2 start = texcoord / u_inverse_size;  // t(x) in pixels
#ifdef IBFVS_COMPENSATE
  // The compensated warp (core/texture/display.h): the bilinear sample plus
  // c times its excess over its two neighbours across the flow, c = s v /
  // reach^2 for v the bilinear weights' variance across the flow, which
  // takes back the blur the sample adds there. Sharpening reads the same
  // two neighbours.
  vec2 across_flow = IBFVS_SHARPEN_REACH * vec2(-along.y, along.x);
  vec4 across_a = vec4(0.0), across_b = vec4(0.0);
  if (same_surface && moved_length > 1e-6) {
    across_a = textureLod(u_previous, (start + across_flow) * u_inverse_size, 0.0);
    across_b = textureLod(u_previous, (start - across_flow) * u_inverse_size, 0.0);
    if (stored_depth(across_a) > -255.0 && stored_depth(across_b) > -255.0) {
      vec2 f = fract(start - 0.5);
      float v = dot(f * (1.0 - f), along.yx * along.yx);
      previous = clamp(previous + u_compensation * v *
                                      (previous - 0.5 * (stored_value(across_a) + stored_value(across_b))),
                       0.0, 1.0);
    }
  }
#endif
#ifdef IBFVS_INJECT_ADD
  if (!same_surface && u_locked == 0) previous = vec3(0.0);  // no ink has arrived yet
#else
  if (!same_surface && u_locked == 0) previous = vec3(g);
#endif
#ifdef IBFVS_INJECT_ADD
  vec3 ft = min(previous * (1.0 - u_alpha) + vec3(g), vec3(1.0));
#else
  vec3 ft = mix(previous, vec3(g), u_alpha);  // equation 10
#endif
  if (u_locked != 0) ft = previous;  // a locked texture is only mapped, never changed
#if defined(IBFVS_SHARPEN) && defined(IBFVS_MONO_TEXTURE)
  // Sharpening once per pixel (display_tap): the high-pass of the last
  // frame's F_t at t(x) across this pixel's flow, and that of this frame's
  // noise at x; F_t's high-pass mixes them as equation 10 mixes the values
  // (t carries x's neighbours to t(x)'s, up to the map's slight stretch and
  // turn in one frame). Off the last frame's surface the value is the noise.
  vec2 across = IBFVS_SHARPEN_REACH * vec2(-along.y, along.x);
#ifdef IBFVS_OBJECT_NOISE
  vec3 object_across = dFdx(v_position_object) * across.x + dFdy(v_position_object) * across.y;
#endif
  float high_previous = 0.0, high_noise = 0.0;
  if (moved_length > 1e-6) {
    if (same_surface) {
#ifdef IBFVS_COMPENSATE
      vec4 a = across_a, b = across_b;  // read for the warp, at the same points
#else
      vec4 a = textureLod(u_previous, (start + across) * u_inverse_size, 0.0);
      vec4 b = textureLod(u_previous, (start - across) * u_inverse_size, 0.0);
#endif
      if (stored_depth(a) > -255.0 && stored_depth(b) > -255.0)
        high_previous = previous.r - 0.5 * (stored_value(a).r + stored_value(b).r);
    }
#ifdef IBFVS_OBJECT_NOISE
    high_noise = g - 0.5 * (solid_noise(v_position_object + object_across) +
                            solid_noise(v_position_object - object_across));
#else
    vec2 here = gl_FragCoord.xy - u_noise_shift;
    high_noise = g - 0.5 * (noise(here + across) + noise(here - across));
#endif
  }
#ifdef IBFVS_INJECT_ADD
  float high = (1.0 - u_alpha) * high_previous + high_noise;  // no ink off the last surface
#else
  float high = same_surface ? mix(high_previous, high_noise, u_alpha) : high_noise;
#endif
  if (u_locked != 0) high = high_previous;
#endif
#ifdef IBFVS_MONO_TEXTURE
  o_texture = vec4(ft.r, depth, along);  // the direction the display filter follows
#else
  o_texture = vec4(ft, depth);
#endif
#ifdef IBFVS_TAP_TEXTURE
  o_taps = vec4(encode_tap_value(ft.r + u_sharpen * high), encode_tap_depth(depth, IBFVS_WRITE_TAP_DEPTH),
                0.5 + 0.5 * along);
#endif
#ifdef IBFVS_RECORD_FLOW
  o_flow = moved;
#endif

  // The displayed texture D(F_t), for display only: F_t stays as synthesised.
  vec3 shown = ft;
#if defined(IBFVS_FILTER) || defined(IBFVS_SHARPEN)
  // The display filter's line starts at t(x) in the last frame's F_t, from
  // the value there sharpened (its first tap).
  bool filtered = same_surface && moved_length > 1e-6;
  if (filtered) {
#if defined(IBFVS_SHARPEN) && defined(IBFVS_MONO_TEXTURE)
    shown = previous + u_sharpen * high_previous;
#else
    shown = display_tap(start, previous, along);
#endif
#if defined(IBFVS_FILTER) && !defined(IBFVS_TAP_TEXTURE)
    shown = display_filter(start, along, previous_depth, shown);
#endif
  }
#endif

  // F_s: Blinn-Phong with a headlight, lit from both sides (open meshes).
  float diffuse = here.diffuse;
  float d2 = diffuse * diffuse, d8 = d2 * d2 * d2 * d2, d32 = d8 * d8 * d8 * d8;
  float specular = d32 * d8;  // diffuse^40: half vector = view for a headlight
  vec3 albedo = u_surface_color;
#ifdef IBFVS_SURFACE_IMAGE
  {
    // Longitude and latitude of the direction from the centre, per pixel (no
    // seam where a triangle crosses the date line): +Y north, +Z longitude 0.
    vec3 d = normalize(v_position_object - u_image_centre);
    float lon = atan(d.x, d.z), lat = asin(clamp(d.y, -1.0, 1.0));
    vec2 uv = vec2(lon / 6.28318530718 + 0.5, lat / 3.14159265359 + 0.5);
    albedo = textureGrad(u_surface_image, uv, vec2(0.0), vec2(0.0)).rgb;
  }
#endif
#ifdef IBFVS_COLOR_SCALAR
  if (!isnan(here.scalars.x)) {  // missing data keeps the surface colour
    float t = clamp((here.scalars.x - u_color_range.x) / (u_color_range.y - u_color_range.x), 0.0, 1.0);
    albedo = textureLod(u_color_map, vec2((t * 255.0 + 0.5) / 256.0, 0.5), 0.0).rgb;
  }
#endif
  vec3 shaded = albedo * (0.18 + 0.82 * diffuse) + vec3(0.25 * specular);
  float beta = u_beta;
#ifdef IBFVS_BETA_SCALAR
  beta *= isnan(here.scalars.y)
              ? 0.0
              : clamp((here.scalars.y - u_beta_range.x) / (u_beta_range.y - u_beta_range.x), 0.0, 1.0);
#endif
#if defined(IBFVS_TAP_TEXTURE) && !defined(IBFVS_RESOLVE)
  o_seed = vec4(shown.r, filtered ? previous_depth : kNoFilter, moved);
  o_color = vec4((1.0 - beta) * shaded, beta);
#else
#if defined(IBFVS_TAP_TEXTURE) && defined(IBFVS_FILTER)
  // As the display pass (display_fragment_main.glsl) from the seed.
  if (filtered) shown = display_filter(start, along, previous_depth, vec3(shown.r));
#endif
  float shown_mean = (shown.r + shown.g + shown.b) / 3.0;
#ifdef IBFVS_CONTRAST
#ifdef IBFVS_TAP_TEXTURE
  shown = contrast(shown, contrast_stage(texelFetch(u_stats, ivec2(0), 0).xyz));
#else
  shown = contrast(shown, v_contrast);
#endif
#endif
  o_color = vec4(beta * shown + (1.0 - beta) * shaded, shown_mean);
#endif
}
