// Twin of ball_lens.lua (POV-Ray 3.7 photon mapping). POV-Ray is
// left-handed; every scene here is symmetric under z -> -z, so the same
// numbers describe the same scene. Count: photons to shoot; Depth: the
// floor below the ball's centre (0.75: the paraxial focus); Height: the
// camera above the floor.
#version 3.7;
#ifndef (Depth) #declare Depth = 0.75; #end
#ifndef (Height) #declare Height = 0.2; #end
#ifndef (Count) #declare Count = 100000; #end
#ifndef (Gather) #declare Gather = 100; #end
// Spacing > 0: photons by their spacing instead of Count, gathered within Radius (issue 53)
#ifndef (Spacing) #declare Spacing = 0; #end
#ifndef (Radius) #declare Radius = 0.05; #end
global_settings { assumed_gamma 1.0 max_trace_level 32
  photons { #if (Spacing > 0) spacing Spacing radius Radius #else count Count #end autostop 0 jitter 0.4 max_trace_level 32 gather 20, Gather } }
camera { perspective location <0, Height - Depth, 0> look_at <0, -Depth, 0> sky <0, 0, -1> right -x up y angle 60 }
light_source { <0, 10, 0> color rgb 1 parallel point_at <0, 0, 0> photons { refraction on reflection on } }
sphere { 0, 0.5 pigment { rgbf 1 } finish { ambient 0 diffuse 0 specular 0 reflection { 0 1 fresnel on } conserve_energy }
  interior { ior 1.5 } photons { target refraction on reflection on } }
plane { y, -Depth pigment { rgb 1 } finish { ambient 0 diffuse 1 brilliance 1 specular 0 } photons { collect on } }
