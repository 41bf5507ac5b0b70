  // The isosurface's fragment: premultiplied colour and window depth of its pixel (none where
  // the engine found no hit), then the render passes' hooks.
  vec4 colour = texture(colourTexture, texCoord);
  if (colour.a <= 0.0) { discard; }
  igaDepth = texture(depthTexture, texCoord).r;
  gl_FragDepth = igaDepth;
  //VTK::DepthPeeling::PreColor
  gl_FragData[0] = vec4(colour.rgb / colour.a, colour.a);
  //VTK::DepthPeeling::Impl
