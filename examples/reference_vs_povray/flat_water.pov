// Twin of flat_water.lua: the water is a box whose top is the surface;
// the camera is inside it.
#version 3.7;
#ifndef (Count) #declare Count = 100000; #end
#ifndef (Gather) #declare Gather = 100; #end
// Spacing > 0: photons by their spacing instead of Count, gathered within Radius (issue 53)
#ifndef (Spacing) #declare Spacing = 0; #end
#ifndef (Radius) #declare Radius = 0.05; #end
global_settings { assumed_gamma 1.0 max_trace_level 32
  photons { #if (Spacing > 0) spacing Spacing radius Radius #else count Count #end autostop 0 jitter 0.4 max_trace_level 32 gather 20, Gather } }
camera { perspective location <0, -0.2, 0> look_at <0, -0.5, 0> sky <0, 0, -1> right -x up y angle 40 }
light_source { <-10 * cos(radians(60)), 10 * sin(radians(60)), 0> color rgb 1 parallel point_at <0, 0, 0>
  photons { refraction on reflection on } }
box { <-3, -0.6, -3>, <3, 0, 3> pigment { rgbf 1 }
  finish { ambient 0 diffuse 0 specular 0 reflection { 0 1 fresnel on } conserve_energy }
  interior { ior 1.33 } photons { target refraction on reflection on } }
plane { y, -0.5 pigment { rgb 1 } finish { ambient 0 diffuse 1 brilliance 1 specular 0 } photons { collect on } }
