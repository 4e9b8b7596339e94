-- The caustics pass of the optics matrix (tests/lua/optics_matrix_test.lua)
-- by name, at its defaults: every case script adds it the same way.
local c = require "caustica"
return function(name, light, water)
  if name == "caustic_volumes" then
    return c.pass.caustic_volumes { light = light, water = water, resolution = c.param("cv_resolution", 0) }
  end
  return c.pass[name] { light = light }
end
