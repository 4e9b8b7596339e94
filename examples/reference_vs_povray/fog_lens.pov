// Twin of fog_lens.lua: media photons (volume caustics) in a box of
// scattering media. Samples: media samples per interval along each ray.
#version 3.7;
#ifndef (Count) #declare Count = 100000; #end
#ifndef (Gather) #declare Gather = 100; #end
// Spacing > 0: photons by their spacing instead of Count, gathered within Radius (issue 53)
#ifndef (Spacing) #declare Spacing = 0; #end
#ifndef (Radius) #declare Radius = 0.05; #end
#ifndef (Samples) #declare Samples = 50; #end
global_settings { assumed_gamma 1.0 max_trace_level 32
  photons { #if (Spacing > 0) spacing Spacing radius Radius #else count Count #end autostop 0 jitter 0.4 max_trace_level 32 gather 20, Gather media 200 } }
camera { perspective location <0, 0.5, 3> look_at <0, 0.5, 0> right -x up y angle 20 }
light_source { <0, 10, 0> color rgb 1 parallel point_at <0, 0, 0> photons { refraction on reflection on } }
sphere { <0, 1.45, 0>, 0.4 pigment { rgbf 1 } finish { ambient 0 diffuse 0 specular 0 reflection { 0 1 fresnel on } conserve_energy }
  interior { ior 1.5 } photons { target refraction on reflection on } }
box { <-1, 0, -1>, <1, 1, 1> pigment { rgbt 1 } hollow
  interior { media { method 3 intervals 1 samples Samples scattering { 1, rgb 0.5 } absorption rgb 0.1 } }
  photons { collect off } }
