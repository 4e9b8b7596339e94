-- Issue 17's comparison: the deforming glass dragon (40K triangles, a GPU
-- deformer). --set technique=huqin|wyman|layered (the refraction: the two
-- interfaces of Hu & Qin and Wyman against every interface) and
-- caustics=none|photons|layered|beams (illumination textures need a rigid
-- object: their transport table is per mesh).
local c = require "caustica"
local technique = c.param("technique", "layered")
local caustics = c.param("caustics", "layered")
local scene = c.scene {
  camera = c.camera { eye = {0.2, 0.9, 1.9}, target = {0, 0.3, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.03, 0.03, 0.03},
}
local sun = scene:add(c.light.spot { position = {1.2, 2.4, 1.6}, direction = {-1.2, -2.2, -1.6}, angle = 30,
                                     intensity = {14, 13, 12} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.7, 0.7, 0.7} } })
local mesh = c.mesh.load(c.asset "dragon_40k.glb")
local dragon = scene:add(c.object { mesh = mesh, material = c.material.glass { ior = 1.5 },
                                    position = {0, -mesh.bounds[1][2], 0} })
dragon.deform = c.deform.glsl [[
  vec3 deform(vec3 p, float t) {
    float h = clamp(p.y + 0.5, 0.0, 1.0);
    float a = 0.12 * h * h * sin(1.5 * t + 3.0 * p.x);
    return vec3(p.x + a, p.y, p.z + 0.5 * a);
  }
]]
local caustic_passes = {
  photons = function() return c.pass.photon_caustics { light = sun } end,
  layered = function() return c.pass.layered_caustics { light = sun } end,
  beams = function() return c.pass.beam_caustics { light = sun } end,
}
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
if caustics ~= "none" then
  assert(caustic_passes[caustics], "caustics: none, photons, layered or beams expected, got " .. tostring(caustics))
  g:add("caustics", caustic_passes[caustics]())
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = caustics ~= "none" and "caustics.irradiance" or nil,
                              specular = false })
if technique == "huqin" or technique == "wyman" then
  g:add("glass", c.pass.refraction { method = technique, color = "shade.color", shadow = "shadow.depth" })
elseif technique == "layered" then
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
else
  error("technique: huqin, wyman or layered expected, got " .. tostring(technique))
end
g:output("glass.color")
return { scene = scene, graph = g, frames = 90, fps = 30, size = {256, 256},
         -- bench --sweep technique=all / choose: the refractions without caustics, then the caustics
         -- under layered refraction; ranked by the whole image's error over the deformation
         techniques = {
           metric = "image",
           { "huqin", set = { technique = "huqin", caustics = "none" },
             points = { { ["glass.lookup"] = "impostors", ["glass.internal"] = 1 } } },
           { "wyman", set = { technique = "wyman", caustics = "none" } },
           { "layered", set = { technique = "layered", caustics = "none" }, sweep = { ["glass.layers"] = {8} } },
           { "layered+photons", set = { technique = "layered", caustics = "photons" },
             points = { { ["caustics.buffer"] = 512, ["caustics.texture"] = 512 } } },
           { "layered+layered", set = { technique = "layered", caustics = "layered" },
             sweep = { ["caustics.buffer"] = {128} } },
           { "layered+beams", set = { technique = "layered", caustics = "beams" },
             points = { { ["caustics.refine"] = 0 } } },
         } }
