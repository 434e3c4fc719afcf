--[[
weave.lua -- pandoc Lua filter that typesets the program chunks of the
literate book as cross-referenced HTML.

Run it on the whole book at once, so references work across chapters:

    pandoc book.md chapters/*.md --lua-filter tools/book/weave.lua -o book.html

A fenced code block is program code when it has chunk="NAME" or file="PATH":

    ```{.c file="vec.h"}                 a root: a file of the program
    ```{.c chunk="vector ops"}           first definition of a chunk
    ```{.c chunk="vector ops" .append}   adds lines to the definition
    ```{.c chunk="shade" .replace}       replaces the body from here on

A code line that holds only <<name>> refers to chunk "name".  Each piece
becomes a <div class="chunk"> with a header (name, kind, chapter, files
it ends up in), the escaped code with links for references, and a footer
(who uses it, where its other pieces are).  A piece whose body is empty, a
hook that later chapters fill, becomes one compact line that says which
chapters fill it.  Blank lines at the start and end of a box are not shown.
Other code blocks are left to pandoc.

The filter also numbers headers so that chapter "{#ch07}" is "Chapter 7"
(in its heading, the table of contents and every cross-reference) even if
earlier chapters are missing; puts previous/next links at the start and the
end of every level-1 section; and appends an index: every chunk and file
with links to all its pieces, and every C function, type, macro and
enumerator the code defines (found by tools/book/weave_names.lua) with a link to
the piece that defines it.

Written for pandoc 2.17 and 3.x (Pandoc:walk, attributes, RawBlock and
the Header/Para/Str constructors; tested with 2.17).  Problems are
reported on stderr as warnings.
]]

local KIND_MARK = { define = "=", append = "+=", replace = ":=" }

-- Everything the first pass learns about the book.
local chapters = {}       -- level-1 headers: { number, title, id }
local pieces = {}         -- every code piece, in document order
local pieces_of = {}      -- key -> list of its pieces, in order
local users_of = {}       -- chunk name -> pieces whose code refers to it
local taken_ids = {}      -- every id already in the document
local section_counter = {} -- current section number at each header level
local current_section = nil -- { number = "1.4" or nil, title, id } of the
                            -- latest header, for the index's piece links
local defined_names = dofile((PANDOC_SCRIPT_FILE and
  PANDOC_SCRIPT_FILE:match("^(.*[/\\])") or "tools/book/") .. "weave_names.lua")

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

-- "Chapter 3", or the title of an unnumbered chapter such as a preface.
local function chapter_label(chapter)
  if not chapter then return "front matter" end
  return chapter.number and ("Chapter " .. chapter.number) or chapter.title
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
-- chapter's number comes from its id.  Pandoc keeps a "number" it finds,
-- and shows it in the heading and the table of contents: a chapter's is
-- "Chapter 7", a section's "7.2".  Returns the chapter number and the
-- section's number as digits ("7.2"), or nil for an unnumbered header.
local function number_header(header)
  if header.classes:includes("unnumbered") then return nil end
  local level = header.level
  local explicit = level == 1 and number_from_id(header.identifier)
  section_counter[level] = explicit or (section_counter[level] or 0) + 1
  for deeper = level + 1, #section_counter do section_counter[deeper] = nil end
  local parts = {}
  for i = 1, level do parts[i] = tostring(section_counter[i] or 0) end
  local digits = table.concat(parts, ".")
  if not header.attributes.number then
    header.attributes.number = level == 1 and ("Chapter " .. digits) or digits
  end
  return section_counter[1], digits
end

local function collect_header(header)
  taken_ids[header.identifier] = true
  local number, digits = number_header(header)
  current_section = { number = digits, id = header.identifier,
                      title = pandoc.utils.stringify(header.content) }
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

-- The language class (e.g. "c"), skipping our own .append/.replace/.exercise
-- marks.
local function piece_language(block)
  for _, class in ipairs(block.classes) do
    if class ~= "append" and class ~= "replace" and class ~= "exercise" then
      return class
    end
  end
  return nil
end

-- An exercise (class .exercise, see tools/workbook/exercises.awk): "Exercise 2.1",
-- numbered from 1 in each chapter, and the tests that grade it.
local exercises_in = {}   -- chapter number -> exercises so far
local function exercise_of(block, chapter)
  if not block.classes:includes("exercise") then return nil end
  local number = chapter and chapter.number
  if not number then
    warn("an exercise outside a numbered chapter")
    return nil
  end
  exercises_in[number] = (exercises_in[number] or 0) + 1
  local tests = {}
  for name in (block.attributes.tests or ""):gmatch("%S+") do
    tests[#tests + 1] = name
  end
  if #tests == 0 then warn("exercise " .. number .. "." .. exercises_in[number]
                           .. " names no tests") end
  return { label = number .. "." .. exercises_in[number], tests = tests }
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
    section = current_section,       -- nil before the first header
    lines = split_lines(block.text),
    refs = {},
    exercise = exercise_of(block, chapters[#chapters]),
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

-- A chunk used and never defined, or defined and never used, is an error:
-- the program would lack code, or the book would show code that is in no
-- program. All are reported, then the weave stops.
local function check_references()
  local errors = 0
  local function report(message)
    io.stderr:write("weave.lua: error: ", message, "\n")
    errors = errors + 1
  end
  for _, name in ipairs(sorted_keys(users_of)) do
    if not pieces_of[chunk_key(name)] then
      local user = users_of[name][1]
      report("<<" .. name .. ">> is used in " .. describe(user) .. " ("
             .. chapter_label(user.chapter) .. ") but never defined")
    end
  end
  for _, key in ipairs(sorted_keys(pieces_of)) do
    local first = pieces_of[key][1]
    if not first.is_file and not users_of[first.name] then
      report(describe(first) .. " is defined but never used")
    end
  end
  if errors > 0 then
    io.stderr:write("weave.lua: ", errors, " chunk reference error(s)\n")
    os.exit(1)
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

-- The lines a box shows: without blank lines at its start and end.
local function shown_lines(piece)
  local first, last = 1, #piece.lines
  while first <= last and not piece.lines[first]:match("%S") do first = first + 1 end
  while last >= first and not piece.lines[last]:match("%S") do last = last - 1 end
  return { table.unpack(piece.lines, first, last) }
end

local function render_code(lines, language)
  local out = {}
  for i, line in ipairs(lines) do
    local indent, name = parse_reference(line)
    out[i] = name and render_reference(indent, name) or escape_html(line)
  end
  local class = language and (' class="language-' .. escape_html(language) .. '"') or ""
  return '<pre class="chunk-code"><code' .. class .. '>' .. table.concat(out, "\n")
    .. '</code></pre>'
end

local function files_phrase(piece)
  local names = {}
  for i, path in ipairs(files_of(piece.key)) do
    names[i] = '<code>' .. escape_html(path) .. '</code>'
  end
  if #names == 0 then return "in no file" end
  return (#names == 1 and "file " or "files ") .. table.concat(names, ", ")
end

local function render_header(piece)
  local where = { '<span class="chunk-chapter">in ' .. chapter_link(piece.chapter) .. '</span>' }
  if not piece.is_file then
    where[2] = '<span class="chunk-files">' .. files_phrase(piece) .. '</span>'
  end
  return '<div class="chunk-header">' .. link(piece.id, piece_label(piece))
    .. ' <span class="chunk-kind">' .. KIND_MARK[piece.kind] .. '</span>'
    .. ' <span class="chunk-where">' .. table.concat(where, " · ") .. '</span></div>'
end

-- "⟨render⟩ (Chapter 2, part 3)" linking to that piece; the part number
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

-- "Chapter 3, Chapter 4": each chapter of the pieces once, linking to the
-- first of its pieces.
local function chapter_links(list)
  local links, seen = {}, {}
  for _, other in ipairs(list) do
    local label = chapter_label(other.chapter)
    if not seen[label] then
      seen[label] = true
      links[#links + 1] = link(other.id, escape_html(label))
    end
  end
  return table.concat(links, ", ")
end

local OTHER_PIECE_VERB = { define = "Defined in", append = "Continued in",
                           replace = "Replaced in" }

local function other_pieces_sentences(piece)
  local by_kind = { define = {}, append = {}, replace = {} }
  for _, other in ipairs(pieces_of[piece.key]) do
    if other ~= piece then table.insert(by_kind[other.kind], other) end
  end
  local sentences = {}
  for _, kind in ipairs({ "define", "append", "replace" }) do
    if #by_kind[kind] > 0 then
      sentences[#sentences + 1] = OTHER_PIECE_VERB[kind] .. " "
        .. chapter_links(by_kind[kind]) .. "."
    end
  end
  return table.concat(sentences, " ")
end

local function render_footer(piece)
  local others = other_pieces_sentences(piece)
  return '<div class="chunk-footer">' .. used_in_sentence(piece)
    .. (others ~= "" and (" " .. others) or "") .. '</div>'
end

local function chunk_div(piece, extra_class)
  return '<div class="chunk chunk-' .. piece.kind .. extra_class .. '" id="' .. piece.id
    .. '" data-' .. (piece.is_file and "file" or "chunk") .. '="' .. escape_html(piece.name)
    .. '" data-chapter="'
    .. escape_html(chapter_label(piece.chapter)) .. '">\n'
end

-- "(empty here; filled in Chapter 6, Chapter 7)": a hook's later pieces.
local function empty_note(piece)
  local later = { table.unpack(pieces_of[piece.key], piece.index + 1) }
  if #later == 0 then return "(empty; no chapter fills it yet)" end
  return "(empty here; filled in " .. chapter_links(later) .. ")"
end

local function render_empty_piece(piece)
  return chunk_div(piece, " chunk-empty")
    .. link(piece.id, piece_label(piece))
    .. ' <span class="chunk-kind">' .. KIND_MARK[piece.kind] .. '</span> '
    .. '<span class="chunk-empty-note">' .. empty_note(piece) .. '</span> '
    .. '· <span class="chunk-where">' .. used_in_sentence(piece) .. '</span>\n</div>'
end

-- "Exercise 2.1 · graded by test_a, test_b · how the workbook works".
local function render_exercise_label(exercise)
  local tests = {}
  for i, name in ipairs(exercise.tests) do
    tests[i] = '<code>' .. escape_html(name) .. '</code>'
  end
  return '<div class="exercise-label"><strong>Exercise ' .. exercise.label
    .. '</strong> · write it yourself: <code>make hint EX=' .. exercise.label
    .. '</code>, <a href="#workbook">how the workbook works</a>'
    .. '<br />graded by ' .. table.concat(tests, ", ") .. '</div>'
end

-- Where the HTML page lets the reader edit a scene and render it with
-- chapter number's program (tools/editions/page/playground.js fills it; it stays
-- empty, and hidden, in a page without the programs). scene: the file's
-- name, or nil for an empty scene of the reader's own. Under a scene, a
-- note that says where to edit it: hidden in the page, but printed where
-- the page has the programs (tools/editions/page/playground.css); in the EPUB
-- where its metadata says that the HTML edition has them (playgrounds:
-- tools/editions/epub.sh).
local PLAYGROUND_NOTE = "The HTML edition of the book (book.html) has a box"
  .. " here that edits this scene and renders it."
local playgrounds_in_html = false
local function playground_html(number, scene)
  if not number then return "" end
  local note = scene and ('\n<p class="playground-note">' .. PLAYGROUND_NOTE .. '</p>') or ""
  if not FORMAT:match("html") then
    return playgrounds_in_html and note or ""
  end
  return '\n<div class="playground" data-chapter="' .. number .. '"'
    .. (scene and (' data-scene="' .. escape_html(scene) .. '"') or "") .. '></div>'
    .. note
end

local function render_piece(piece)
  local lines = shown_lines(piece)
  if #lines == 0 then return render_empty_piece(piece) end
  local scene = piece.is_file and piece.name:match("%.scene$")
  return chunk_div(piece, piece.exercise and " chunk-exercise" or "")
    .. (piece.exercise and render_exercise_label(piece.exercise) or "")
    .. render_header(piece) .. "\n"
    .. render_code(lines, piece.language) .. "\n"
    .. render_footer(piece) .. "\n</div>"
    .. (scene and playground_html(piece.chapter and piece.chapter.number, piece.name) or "")
end

-- An exercise's notes: the task shown, the hint folded away.
local function render_exercise_notes(div)
  if not div.classes:includes("exercise-notes") then return nil end
  local blocks = {}
  for _, block in ipairs(div.content) do
    local first = block.t == "Para" and block.content[1]
    if first and first.t == "Strong" and pandoc.utils.stringify(first) == "Hint." then
      table.remove(block.content, 1)
      blocks[#blocks + 1] = pandoc.RawBlock("html",
        '<details class="exercise-hint"><summary>Hint</summary>')
      blocks[#blocks + 1] = block
      blocks[#blocks + 1] = pandoc.RawBlock("html", '</details>')
    else
      blocks[#blocks + 1] = block
    end
  end
  div.content = blocks
  return div
end

local function render_code_block(block)
  local number = tonumber(block.attributes["weave-piece"] or "")
  if not number then return nil end
  return pandoc.RawBlock("html", render_piece(pieces[number]))
end

---------------------------------------------------------------------
-- The index: chunks and files, then the C names the code defines
---------------------------------------------------------------------

-- A free id for an index header: "index", or "index_2" if a chapter took it.
local function free_id(wanted)
  local id, attempt = wanted, 1
  while taken_ids[id] do
    attempt = attempt + 1
    id = wanted .. "_" .. attempt
  end
  taken_ids[id] = true
  return id
end

-- Where a piece is, shortest: "1.4", or its section's title when unnumbered.
local function section_label(piece)
  local section = piece.section
  if not section then return chapter_label(piece.chapter) end
  return section.number or section.title
end

local function sort_name(text)
  return text:lower():gsub("^[^%w]+", "")
end

local function sorted_by_name(list, name_of)
  table.sort(list, function(a, b)
    local ka, kb = sort_name(name_of(a)), sort_name(name_of(b))
    if ka ~= kb then return ka < kb end
    return name_of(a) < name_of(b)
  end)
  return list
end

-- "= 1.4, += 2.3, 3.5": every piece of a chunk, grouped by kind in order.
local function piece_links(key_pieces)
  local parts, last_kind = {}, nil
  for _, piece in ipairs(key_pieces) do
    local mark = piece.kind ~= last_kind and (KIND_MARK[piece.kind] .. " ") or ""
    last_kind = piece.kind
    parts[#parts + 1] = mark .. link(piece.id, escape_html(section_label(piece)),
      chapter_label(piece.chapter))
  end
  return table.concat(parts, ", ")
end

local function chunk_index_html()
  local keys = sorted_by_name(sorted_keys(pieces_of),
    function(key) return pieces_of[key][1].name end)
  local items = {}
  for i, key in ipairs(keys) do
    local key_pieces = pieces_of[key]
    items[i] = '<li>' .. piece_label(key_pieces[1]) .. ' <span class="index-refs">'
      .. piece_links(key_pieces) .. '</span></li>'
  end
  return '<ul class="book-index">\n' .. table.concat(items, "\n") .. '\n</ul>'
end

-- Prototypes of functions that are defined in the book say nothing new.
local function without_known_prototypes(list, by_name)
  local kept = {}
  for _, entry in ipairs(list) do
    if entry.kind ~= "declared" or not by_name[entry.name .. "\0function"] then
      kept[#kept + 1] = entry
    end
  end
  return kept
end

-- { name, kind, places = { piece, ... } } for every name the C pieces define.
local function collect_names()
  local by_name, list = {}, {}
  for _, piece in ipairs(pieces) do
    if piece.language == "c" then
      for _, found in ipairs(defined_names(piece.lines)) do
        local key = found.name .. "\0" .. found.kind
        if not by_name[key] then
          by_name[key] = { name = found.name, kind = found.kind, places = {} }
          list[#list + 1] = by_name[key]
        end
        table.insert(by_name[key].places, piece)
      end
    end
  end
  return sorted_by_name(without_known_prototypes(list, by_name),
    function(entry) return entry.name end)
end

local function name_item(entry)
  local places = {}
  for i, piece in ipairs(entry.places) do
    places[i] = link(piece.id, piece_label(piece) .. " " .. escape_html(section_label(piece)),
      chapter_label(piece.chapter))
  end
  local kind = entry.kind == "declared" and "function, declared" or entry.kind
  return '<li><code>' .. escape_html(entry.name) .. '</code> <span class="index-kind">'
    .. kind .. '</span> <span class="index-refs">' .. table.concat(places, ", ")
    .. '</span></li>'
end

-- Letters as small headings within the list, so that a long list is scanned.
local function names_index_html()
  local items, letter = {}, nil
  for _, entry in ipairs(collect_names()) do
    local first = sort_name(entry.name):sub(1, 1):upper()
    if first ~= letter then
      letter = first
      items[#items + 1] = '<li class="index-letter">' .. escape_html(first) .. '</li>'
    end
    items[#items + 1] = name_item(entry)
  end
  return '<ul class="book-index">\n' .. table.concat(items, "\n") .. '\n</ul>'
end

local function index_blocks()
  local intro = "Every chunk and file of the program, with links to its pieces "
    .. "(by section; = defines, += continues, := replaces), and every C function, "
    .. "type, macro and enumeration constant the code defines."
  return {
    pandoc.Header(1, { pandoc.Str("Index") },
      pandoc.Attr(free_id("index"), { "unnumbered" })),
    pandoc.Para({ pandoc.Str(intro) }),
    pandoc.Header(2, { pandoc.Str("Chunks and files") },
      pandoc.Attr(free_id("index-chunks"), { "unnumbered" })),
    pandoc.RawBlock("html", chunk_index_html()),
    pandoc.Header(2, { pandoc.Str("Functions, types, macros and constants") },
      pandoc.Attr(free_id("index-names"), { "unnumbered" })),
    pandoc.RawBlock("html", names_index_html()),
  }
end

---------------------------------------------------------------------
-- Previous/next links at the start and end of every level-1 section
---------------------------------------------------------------------

-- "Chapter 2: Spheres", or "Preface" for an unnumbered one.
local function nav_label(header)
  local title = pandoc.utils.stringify(header.content)
  local number = header.attributes.number
  return number and (number .. ": " .. title) or title
end

-- where: "start" or "end" of the section, a class for the style sheet.
local function nav_html(where, previous, next_one)
  local parts = {}
  if previous then
    parts[#parts + 1] = '<a class="nav-previous" rel="prev" href="#' .. escape_html(previous.identifier)
      .. '">← ' .. escape_html(nav_label(previous)) .. '</a>'
  end
  if next_one then
    parts[#parts + 1] = '<a class="nav-next" rel="next" href="#' .. escape_html(next_one.identifier)
      .. '">' .. escape_html(nav_label(next_one)) .. ' →</a>'
  end
  return pandoc.RawBlock("html", '<nav class="chapter-nav chapter-nav-' .. where .. '">'
    .. table.concat(parts, " ") .. '</nav>')
end

-- Copies blocks, adding a nav after each level-1 header and before the
-- next one (and at the end of the last section); a numbered chapter ends
-- with an empty scene to write (playground_html).
local function with_chapter_navs(blocks)
  local headers = {}
  for i, block in ipairs(blocks) do
    if block.t == "Header" and block.level == 1 then headers[#headers + 1] = i end
  end
  local out, k = {}, 0
  local function end_of(header)
    local number = number_from_id(header.identifier)
    if number and playground_html(number) ~= "" then
      out[#out + 1] = pandoc.RawBlock("html", playground_html(number))
    end
  end
  for i, block in ipairs(blocks) do
    if block.t == "Header" and block.level == 1 then
      if k > 0 then
        end_of(blocks[headers[k]])
        out[#out + 1] = nav_html("end", blocks[headers[k - 1]], block)
      end
      k = k + 1
      out[#out + 1] = block
      out[#out + 1] = nav_html("start", k > 1 and blocks[headers[k - 1]], blocks[headers[k + 1]])
    else
      out[#out + 1] = block
    end
  end
  if k > 0 then
    end_of(blocks[headers[k]])
    out[#out + 1] = nav_html("end", blocks[headers[k - 1]], nil)
  end
  return out
end

---------------------------------------------------------------------
-- The filter: both passes over the whole document
---------------------------------------------------------------------

function Pandoc(doc)
  local playgrounds = doc.meta.playgrounds
  playgrounds_in_html = playgrounds == true
    or (playgrounds ~= nil and pandoc.utils.stringify(playgrounds) == "true")
  doc = doc:walk({
    Header = collect_header,
    CodeBlock = collect_code_block,
    Div = collect_id, Span = collect_id, Code = collect_id,
    Link = collect_id, Image = collect_id,
  })
  assign_ids()
  check_references()
  if FORMAT:match("html") or FORMAT:match("epub") then
    doc = doc:walk({ CodeBlock = render_code_block, Div = render_exercise_notes })
    for _, block in ipairs(index_blocks()) do doc.blocks:insert(block) end
    doc.blocks = pandoc.List(with_chapter_navs(doc.blocks))
  end
  return doc
end
