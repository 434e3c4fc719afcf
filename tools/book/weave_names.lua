--[[
weave_names.lua -- the C names a piece of code defines, for the book's index.
tools/book/weave.lua loads it with dofile(); it returns one function:

    local names = defined_names(lines)   -- lines: the piece's code lines
    -- names = { { name = "camera_ray", kind = "function" }, ... }

Simple line patterns, not a C parser.  A name is found when it is
  - a function:  a line at column 0 "TYPE... name(" (after a return type,
                 not a keyword) whose parameter list is followed by "{",
                 not by ";" (a prototype); "int F(geometric)(..." gives the
                 name "F(geometric)", a function named through a macro;
  - a prototype: the same line followed by ";" (kind "declared"), so that
                 functions only named through a macro can be found too;
  - a type:      "typedef ... name;", "typedef R (*name)(...);",
                 "typedef struct/enum/union {...} name;" (the "}" on a later
                 line), and "struct name {" at column 0 ("struct name");
  - a macro:     "#define NAME", except an include guard (a "#define NAME"
                 with no value right after "#ifndef NAME");
  - a constant:  an enumerator between the braces of an "enum {...}".
Comments are removed first; a piece's "<<chunk>>" lines are only text here.
]]

local NOT_A_RETURN_TYPE = { ["return"] = true, ["typedef"] = true, ["else"] = true,
  ["goto"] = true, ["case"] = true, ["sizeof"] = true, ["if"] = true,
  ["while"] = true, ["for"] = true, ["switch"] = true, ["do"] = true }

-- The lines without /* */ and // comments (a comment may span lines).
local function strip_comments(lines)
  local out, in_comment = {}, false
  for i, line in ipairs(lines) do
    local kept, pos = {}, 1
    while pos <= #line do
      if in_comment then
        local close = line:find("*/", pos, true)
        if not close then pos = #line + 1 else in_comment = false; pos = close + 2 end
      else
        local open = line:find("/[*/]", pos)
        if not open then kept[#kept + 1] = line:sub(pos); break end
        kept[#kept + 1] = line:sub(pos, open - 1)
        if line:sub(open + 1, open + 1) == "/" then break end
        in_comment, pos = true, open + 2
      end
    end
    out[i] = table.concat(kept)
  end
  return out
end

-- Is the "(" at lines[i]:sub(col) the start of a body ("{" comes before ";")?
local function has_body(lines, i, col)
  for j = i, math.min(i + 8, #lines) do
    local text = (j == i) and lines[j]:sub(col) or lines[j]
    local brace, semicolon = text:find("{", 1, true), text:find(";", 1, true)
    if brace and (not semicolon or brace < semicolon) then return true end
    if semicolon then return false end
  end
  return false
end

local function function_name(lines, i)
  local line = lines[i]
  local prefix, name, col = line:match("^([%a_][%w_%s%*]-[%s%*])([%a_][%w_]*)%s*()%(")
  if not name then return nil end
  local first = prefix:match("^([%a_][%w_]*)")
  if NOT_A_RETURN_TYPE[first] or NOT_A_RETURN_TYPE[name] then return nil end
  local through_macro, after = line:match("^(%([%w_]+%))%s*()%(", col)
  if through_macro then name, col = name .. through_macro, after end
  return name, has_body(lines, i, col)
end

local function macro_name(lines, i)
  local name, value = lines[i]:match("^%s*#%s*define%s+([%a_][%w_]*)(.*)$")
  if not name then return nil end
  if value:match("^%s*$") then
    for j = i - 1, 1, -1 do
      if lines[j]:match("%S") then
        if lines[j]:match("^%s*#%s*ifndef%s+" .. name .. "%s*$") then return nil end
        break
      end
    end
  end
  return name
end

-- Enumerators in the text between an enum's braces.
local function add_enumerators(text, add)
  for item in (text .. ","):gmatch("([^,]*),") do
    local name = item:match("^%s*([%a_][%w_]*)")
    if name then add(name, "constant") end
  end
end

-- Follows typedef/enum bodies across lines: state.open is "typedef" while
-- a typedef's braces are open, state.enum while inside an enum's braces.
local function scan_type_line(line, state, add)
  if state.enum then
    local body, closed = line:match("^([^}]*)(}?)")
    add_enumerators(body, add)
    if closed == "}" then state.enum = false end
  elseif line:match("^%s*typedef%s") or line:match("^enum[%s{]") then
    local after_brace = line:match("enum[^;{]*{(.*)$")
    if after_brace then
      local body, closed = after_brace:match("^([^}]*)(}?)")
      add_enumerators(body, add)
      state.enum = closed ~= "}"
    end
  end
  local tag = line:match("^struct%s+([%a_][%w_]*)%s*{")
  if tag then add("struct " .. tag, "type") end
  if line:match("^%s*typedef%s") then
    local opens = select(2, line:gsub("{", "")) > select(2, line:gsub("}", ""))
    if opens then state.typedef = true; return end
    local name = line:match("%(%s*%*%s*([%a_][%w_]*)%s*%)%s*%(")
      or line:match("([%a_][%w_]*)%s*;%s*$")
    if name then add(name, "type") end
  elseif state.typedef then
    local name = line:match("^}%s*([%a_][%w_]*)%s*;")
    if name then add(name, "type"); state.typedef = false end
  end
end

return function(code_lines)
  local lines = strip_comments(code_lines)
  local found, seen = {}, {}
  local function add(name, kind)
    if not seen[name .. " " .. kind] then
      seen[name .. " " .. kind] = true
      found[#found + 1] = { name = name, kind = kind }
    end
  end
  local state = {}
  for i, line in ipairs(lines) do
    local fn, defined = function_name(lines, i)
    if fn then add(fn, defined and "function" or "declared") end
    local macro = macro_name(lines, i)
    if macro then add(macro, "macro") end
    scan_type_line(line, state, add)
  end
  return found
end
