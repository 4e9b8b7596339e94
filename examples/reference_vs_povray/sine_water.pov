// Twin of sine_water.lua: the water body is an isosurface below the ridged
// surface, cut to a box.
#version 3.7;
#ifndef (Count) #declare Count = 100000; #end
#ifndef (Gather) #declare Gather = 100; #end
// Spacing > 0: photons by their spacing instead of Count, gathered within Radius (issue 53)
#ifndef (Spacing) #declare Spacing = 0; #end
#ifndef (Radius) #declare Radius = 0.05; #end
global_settings { assumed_gamma 1.0 max_trace_level 32
  photons { #if (Spacing > 0) spacing Spacing radius Radius #else count Count #end autostop 0 jitter 0.4 max_trace_level 32 gather 20, Gather } }
camera { perspective location <0.000853, -0.2, 0> look_at <0.000853, -0.5, 0> sky <0, 0, -1> right -x up y angle 40 }
light_source { <0, 10, 0> color rgb 1 parallel point_at <0, 0, 0> photons { refraction on reflection on } }
isosurface {
  function { y - 0.06 * cos(2 * pi * x / 0.5) }
  contained_by { box { <-1.5, -0.6, -1.5>, <1.5, 0.07, 1.5> } }
  accuracy 0.00001 max_gradient 1.5
  pigment { rgbf 1 } finish { ambient 0 diffuse 0 specular 0 reflection { 0 1 fresnel on } conserve_energy }
  interior { ior 1.33 } photons { target refraction on reflection on } }
plane { y, -0.5 pigment { rgb 1 } finish { ambient 0 diffuse 1 brilliance 1 specular 0 } photons { collect on } }
