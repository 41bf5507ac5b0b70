// Declarations of the isosurface's full-screen pass: the engine's frame as two textures, and
// the surface's window depth, which replaces gl_FragCoord.z in the render passes' hooks.
uniform sampler2D colourTexture;
uniform sampler2D depthTexture;
float igaDepth;
//VTK::DepthPeeling::Dec
