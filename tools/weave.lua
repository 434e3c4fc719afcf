--[[
weave.lua -- pandoc Lua filter that typesets the program chunks of the
literate book as cross-referenced HTML.

Run it on the whole book at once, so references work across chapters:

    pandoc book.md chapters/*.md --lua-filter tools/weave.lua -o book.html

A fenced code block is program code when it has chunk="NAME" or file="PATH":

    ```{.c file="vec.h"}                 a root: a file of the program
    ```{.c chunk="vector ops"}           first definition of a chunk
    ```{.c chunk="vector ops" .append}   adds lines to the definition
    ```{.c chunk="shade" .replace}       replaces the body from here on

A code line that holds only <<name>> refers to chunk "name".  Each piece
becomes a <div class="chunk"> with a header (name, kind, chapter, files
it ends up in), the escaped code with links for references, and a footer
(who uses it, where its other pieces are).  Other code blocks are left to
pandoc.  The filter also numbers headers so that chapter "{#ch07}" is
chapter 7 even if earlier chapters are missing.

Works with pandoc 2.17 and 3.x (only Pandoc:walk, attributes and
RawBlock are used).  Problems are reported on stderr as warnings.
]]

local KIND_MARK = { define = "=", append = "+=", replace = ":=" }

-- Everything the first pass learns about the book.
local chapters = {}       -- level-1 headers: { number, title, id }
local pieces = {}         -- every code piece, in document order
local pieces_of = {}      -- key -> list of its pieces, in order
local users_of = {}       -- chunk name -> pieces whose code refers to it
local taken_ids = {}      -- every id already in the document
local section_counter = {} -- current section number at each header level

---------------------------------------------------------------------
-- Small helpers
---------------------------------------------------------------------

local function warn(message)
  io.stderr:write("weave.lua: warning: ", message, "\n")
end

local HTML_ESCAPES = { ["&"] = "&amp;", ["<"] = "&lt;", [">"] = "&gt;",
                       ['"'] = "&quot;" }

local function escape_html(text)
  return (text:gsub('[&<>"]', HTML_ESCAPES))
end

local function trim(text)
  return (text:match("^%s*(.-)%s*$"))
end

-- "ch. 3", or the title of an unnumbered chapter such as a preface.
local function chapter_label(chapter)
  if not chapter then return "front matter" end
  return chapter.number and ("ch. " .. chapter.number) or chapter.title
end

-- "Vector ops (2)" -> "vector-ops-2": a readable, URL-safe id part.
local function slugify(name)
  local slug = name:lower():gsub("[^%w]+", "-"):gsub("^%-+", ""):gsub("%-+$", "")
  if slug == "" then slug = "x" end
  return slug
end

local function split_lines(text)
  local lines = {}
  for line in (text .. "\n"):gmatch("(.-)\n") do
    lines[#lines + 1] = line
  end
  return lines
end

-- A reference line is "<<name>>" alone, maybe indented; returns indent, name.
local function parse_reference(line)
  local indent, name = line:match("^(%s*)<<(.-)>>%s*$")
  if name and trim(name) ~= "" then
    return indent, trim(name)
  end
  return nil
end

-- How a piece is named in warnings: <<chunk name>> or the file's path.
local function describe(piece)
  return piece.is_file and piece.name or ("<<" .. piece.name .. ">>")
end

-- Chunks and files live in separate name spaces: <<x>> never means file x.
local function chunk_key(name) return "chunk:" .. name end
local function file_key(path) return "file:" .. path end

---------------------------------------------------------------------
-- Pass 1: collect chapters and pieces
---------------------------------------------------------------------

-- Chapter number from an id like "ch07", so it matches chapters/07-*.md.
local function number_from_id(id)
  local digits = id:match("^ch(%d+)$")
  return digits and tonumber(digits)
end

-- Pandoc numbers sections by counting; we set the number ourselves so a
-- chapter's number comes from its id.  Pandoc keeps a "number" it finds.
local function number_header(header)
  if header.classes:includes("unnumbered") then return nil end
  local level = header.level
  local explicit = level == 1 and number_from_id(header.identifier)
  section_counter[level] = explicit or (section_counter[level] or 0) + 1
  for deeper = level + 1, #section_counter do section_counter[deeper] = nil end
  local parts = {}
  for i = 1, level do parts[i] = tostring(section_counter[i] or 0) end
  if not header.attributes.number then
    header.attributes.number = table.concat(parts, ".")
  end
  return section_counter[1]
end

local function collect_header(header)
  taken_ids[header.identifier] = true
  local number = number_header(header)
  if header.level == 1 then
    chapters[#chapters + 1] = {
      number = number,
      title = pandoc.utils.stringify(header.content),
      id = header.identifier,
    }
  end
  return header
end

local function piece_kind(block)
  if block.classes:includes("replace") then return "replace" end
  if block.classes:includes("append") then return "append" end
  return "define"
end

-- The language class (e.g. "c"), skipping our own .append/.replace marks.
local function piece_language(block)
  for _, class in ipairs(block.classes) do
    if class ~= "append" and class ~= "replace" then return class end
  end
  return nil
end

local function check_kind(piece, earlier_count)
  local what = describe(piece)
  if piece.kind == "define" and earlier_count > 0 then
    warn(what .. " is defined again; use .append or .replace")
  elseif piece.kind ~= "define" and earlier_count == 0 then
    warn(what .. " has ." .. piece.kind .. " before any definition")
  end
end

local function new_piece(block)
  local path, name = block.attributes.file, block.attributes.chunk
  if path and name then
    warn("code block has both file=\"" .. path .. "\" and chunk=\"" .. name
         .. "\"; using the file")
  end
  local is_file = path ~= nil
  local piece = {
    is_file = is_file,
    name = trim(is_file and path or name),
    kind = piece_kind(block),
    language = piece_language(block),
    chapter = chapters[#chapters],   -- nil before the first chapter
    lines = split_lines(block.text),
    refs = {},
  }
  piece.key = is_file and file_key(piece.name) or chunk_key(piece.name)
  return piece
end

local function register_piece(piece)
  local siblings = pieces_of[piece.key] or {}
  check_kind(piece, #siblings)
  siblings[#siblings + 1] = piece
  pieces_of[piece.key] = siblings
  piece.index = #siblings
  pieces[#pieces + 1] = piece
  for _, line in ipairs(piece.lines) do
    local _, name = parse_reference(line)
    if name and not piece.refs[name] then
      piece.refs[name] = true
      users_of[name] = users_of[name] or {}
      table.insert(users_of[name], piece)
    end
  end
end

local function collect_code_block(block)
  taken_ids[block.identifier] = true
  if not (block.attributes.chunk or block.attributes.file) then return nil end
  local piece = new_piece(block)
  register_piece(piece)
  -- Remember which piece this block is, for the second pass.
  block.attributes["weave-piece"] = tostring(#pieces)
  return block
end

local function collect_id(element)
  taken_ids[element.identifier] = true
  return nil
end

---------------------------------------------------------------------
-- Between the passes: ids and the files each chunk ends up in
---------------------------------------------------------------------

-- Every piece of a key gets base, base-2, base-3, ...; if another name
-- slugifies to the same base, try base_2, base_3, ... until all are free.
local function ids_are_free(base, count)
  if taken_ids[base] then return false end
  for i = 2, count do
    if taken_ids[base .. "-" .. i] then return false end
  end
  return true
end

local function assign_ids_to(key_pieces)
  local first = key_pieces[1]
  local prefix = first.is_file and "file-" or "chunk-"
  local stem = prefix .. slugify(first.name)
  local base, attempt = stem, 1
  while not ids_are_free(base, #key_pieces) do
    attempt = attempt + 1
    base = stem .. "_" .. attempt
  end
  for i, piece in ipairs(key_pieces) do
    piece.id = (i == 1) and base or (base .. "-" .. i)
    taken_ids[piece.id] = true
  end
end

local function assign_ids()
  for _, piece in ipairs(pieces) do
    if piece.index == 1 then assign_ids_to(pieces_of[piece.key]) end
  end
end

local function sorted_keys(set)
  local list = {}
  for key in pairs(set) do list[#list + 1] = key end
  table.sort(list)
  return list
end

-- Follow "who refers to me" up to the roots; memoised, cycle-safe.
local files_cache = {}
local cycles_reported = {}
local function files_of(key, visiting)
  if files_cache[key] then return files_cache[key] end
  local first = pieces_of[key] and pieces_of[key][1]
  if first and first.is_file then return { first.name } end
  visiting = visiting or {}
  if visiting[key] then
    -- Tangling would expand this chunk inside itself forever.
    if first and not cycles_reported[key] then
      cycles_reported[key] = true
      warn(describe(first) .. " is part of a reference cycle")
    end
    return {}
  end
  visiting[key] = true
  local found = {}
  for _, user in ipairs(users_of[first and first.name or ""] or {}) do
    for _, path in ipairs(files_of(user.key, visiting)) do found[path] = true end
  end
  visiting[key] = nil
  files_cache[key] = sorted_keys(found)
  return files_cache[key]
end

local function warn_about_references()
  for _, name in ipairs(sorted_keys(users_of)) do
    if not pieces_of[chunk_key(name)] then
      local user = users_of[name][1]
      warn("<<" .. name .. ">> is used in " .. describe(user) .. " ("
           .. chapter_label(user.chapter) .. ") but never defined")
    end
  end
  for _, key in ipairs(sorted_keys(pieces_of)) do
    local first = pieces_of[key][1]
    if not first.is_file and not users_of[first.name] then
      warn(describe(first) .. " is defined but never used")
    end
  end
end

---------------------------------------------------------------------
-- Pass 2: render each piece as HTML
---------------------------------------------------------------------

local function link(id, inner_html, title)
  local title_attr = title and (' title="' .. escape_html(title) .. '"') or ""
  return '<a href="#' .. escape_html(id) .. '"' .. title_attr .. '>' .. inner_html .. '</a>'
end

-- ⟨name⟩ for a chunk, the path in code type for a file.
local function piece_label(piece)
  if piece.is_file then
    return '<code class="chunk-file">' .. escape_html(piece.name) .. '</code>'
  end
  return '<span class="chunk-name">⟨' .. escape_html(piece.name) .. '⟩</span>'
end

local function chapter_link(chapter)
  local label = escape_html(chapter_label(chapter))
  if not chapter or chapter.id == "" then return label end
  return link(chapter.id, label, chapter.title)
end

local function render_reference(indent, name)
  local target = pieces_of[chunk_key(name)]
  local label = "⟨" .. escape_html(name) .. "⟩"
  if not target then
    -- No link: a visible mark instead of a link that goes nowhere.
    return escape_html(indent) .. '<span class="chunk-ref chunk-undefined"'
      .. ' title="this chunk is never defined">' .. label
      .. ' <strong>(undefined)</strong></span>'
  end
  return escape_html(indent) .. '<a class="chunk-ref" href="#' .. target[1].id
    .. '">' .. label .. '</a>'
end

local function render_code(piece)
  local out = {}
  for i, line in ipairs(piece.lines) do
    local indent, name = parse_reference(line)
    out[i] = name and render_reference(indent, name) or escape_html(line)
  end
  local class = piece.language and (' class="language-' .. escape_html(piece.language) .. '"') or ""
  return '<pre class="chunk-code"><code' .. class .. '>' .. table.concat(out, "\n")
    .. '</code></pre>'
end

local function render_header(piece)
  local where = { '<span class="chunk-chapter">in ' .. chapter_link(piece.chapter)
    .. (piece.chapter and piece.chapter.number and (" " .. escape_html(piece.chapter.title)) or "")
    .. '</span>' }
  if not piece.is_file then
    local files = files_of(piece.key)
    local names = {}
    for i, path in ipairs(files) do
      names[i] = '<code>' .. escape_html(path) .. '</code>'
    end
    where[#where + 1] = '<span class="chunk-files">'
      .. (#names == 0 and "in no file" or ((#names == 1 and "file " or "files ")
          .. table.concat(names, ", ")))
      .. '</span>'
  end
  return '<div class="chunk-header">' .. link(piece.id, piece_label(piece))
    .. ' <span class="chunk-kind">' .. KIND_MARK[piece.kind] .. '</span>'
    .. ' <span class="chunk-where">' .. table.concat(where, " · ") .. '</span></div>'
end

-- "⟨render⟩ (ch. 2, part 3)" linking to that piece; the part number
-- tells apart several pieces of one chunk.
local function piece_link(piece)
  local part = piece.index > 1 and (", part " .. piece.index) or ""
  return link(piece.id, piece_label(piece) .. " (" .. escape_html(chapter_label(piece.chapter))
    .. part .. ")")
end

local function used_in_sentence(piece)
  if piece.is_file then return "Root file." end
  local users = users_of[piece.name] or {}
  if #users == 0 then return "Never used." end
  local links = {}
  for i, user in ipairs(users) do links[i] = piece_link(user) end
  return "Used in " .. table.concat(links, ", ") .. "."
end

local OTHER_PIECE_VERB = { define = "Defined in", append = "Continued in",
                           replace = "Replaced in" }

local function other_pieces_sentences(piece)
  local by_kind = { define = {}, append = {}, replace = {} }
  for _, other in ipairs(pieces_of[piece.key]) do
    if other ~= piece then
      local list = by_kind[other.kind]
      list[#list + 1] = link(other.id, escape_html(chapter_label(other.chapter)))
    end
  end
  local sentences = {}
  for _, kind in ipairs({ "define", "append", "replace" }) do
    if #by_kind[kind] > 0 then
      sentences[#sentences + 1] = OTHER_PIECE_VERB[kind] .. " "
        .. table.concat(by_kind[kind], ", ") .. "."
    end
  end
  return table.concat(sentences, " ")
end

local function render_footer(piece)
  local others = other_pieces_sentences(piece)
  return '<div class="chunk-footer">' .. used_in_sentence(piece)
    .. (others ~= "" and (" " .. others) or "") .. '</div>'
end

local function render_piece(piece)
  return '<div class="chunk chunk-' .. piece.kind .. '" id="' .. piece.id .. '">\n'
    .. render_header(piece) .. "\n"
    .. render_code(piece) .. "\n"
    .. render_footer(piece) .. "\n</div>"
end

local function render_code_block(block)
  local number = tonumber(block.attributes["weave-piece"] or "")
  if not number then return nil end
  return pandoc.RawBlock("html", render_piece(pieces[number]))
end

---------------------------------------------------------------------
-- The filter: both passes over the whole document
---------------------------------------------------------------------

function Pandoc(doc)
  doc = doc:walk({
    Header = collect_header,
    CodeBlock = collect_code_block,
    Div = collect_id, Span = collect_id, Code = collect_id,
    Link = collect_id, Image = collect_id,
  })
  assign_ids()
  warn_about_references()
  if FORMAT:match("html") then
    doc = doc:walk({ CodeBlock = render_code_block })
  end
  return doc
end
