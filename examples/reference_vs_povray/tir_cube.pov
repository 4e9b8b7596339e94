// Twin of tir_cube.lua.
#version 3.7;
#ifndef (Count) #declare Count = 100000; #end
#ifndef (Gather) #declare Gather = 100; #end
// Spacing > 0: photons by their spacing instead of Count, gathered within Radius (issue 53)
#ifndef (Spacing) #declare Spacing = 0; #end
#ifndef (Radius) #declare Radius = 0.05; #end
global_settings { assumed_gamma 1.0 max_trace_level 32
  photons { #if (Spacing > 0) spacing Spacing radius Radius #else count Count #end autostop 0 jitter 0.4 max_trace_level 32 gather 20, Gather } }
camera { perspective location <0.25, -0.6, 0> look_at <0.25, -1.0, 0> sky <0, 0, -1> right -x up y angle 90 }
light_source { <-10 * sin(radians(30)), 10 * cos(radians(30)), 0> color rgb 1 parallel point_at <0, 0, 0>
  photons { refraction on reflection on } }
box { <-0.5, -0.5, -0.5>, <0.5, 0.5, 0.5> pigment { rgbf 1 }
  finish { ambient 0 diffuse 0 specular 0 reflection { 0 1 fresnel on } conserve_energy }
  interior { ior 2.42 } photons { target refraction on reflection on } }
plane { y, -1.0 pigment { rgb 1 } finish { ambient 0 diffuse 1 brilliance 1 specular 0 } photons { collect on } }
