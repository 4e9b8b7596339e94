-- Tries what a sandboxed script may not do: --set try=execute|popen|write|loadlib|none
local c = require "caustica"
local try = c.param("try", "none")
if try == "execute" then os.execute("true")
elseif try == "popen" then io.popen("true")
elseif try == "write" then io.open("/tmp/caustica-sandbox-escape.txt", "w")
elseif try == "loadlib" then package.loadlib("libc.so.6", "puts")
end
local scene = c.scene {}
local g = c.graph()
g:add("env", c.pass.environment {})
g:output("env.color")
return { scene = scene, graph = g, size = {16, 16} }
