// What an object is, as the scene decides it (scene.h's enum object_role,
// the same bits; tests/unit/test_program.c holds them equal), set on every
// object the renderer draws as u_object_role: the one vocabulary of roles
// from the scene to the shaders, where shaders tested material kinds
// (issue 54).
const int ROLE_RECEIVER = 1; // diffuse: lit, shadowed, receives caustics
const int ROLE_GLASS = 2;    // a closed refractor
const int ROLE_WATER = 4;    // a water surface, its medium below
const int ROLE_MIRROR = 8;
const int ROLE_THIN = 16;    // thin-walled glass: light crosses it undeviated

uniform int u_object_role;

bool role_is(int role) { return (u_object_role & role) != 0; }
