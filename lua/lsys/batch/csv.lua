--- CSV text (RFC 4180) as lsys.batch reads its specs: records with the line each begins on.
-- @module lsys.batch.csv
local type, error, select = type, error, select
local string, table = string, table
local format = string.format
local _ENV = nil

local M = {}

-- The next record of the CSV text `text` of the file `name` from byte `i`, on line `line`
-- (blank lines skipped): the record (a list of fields with `line`), and the byte and line
-- after it; nil when the text ends. Raises as M.csv.
local function csv_record (text, i, line, name)
  local len = #text
  local function fail (l, msg) error(format("%s:%d: %s", name, l, msg), 0) end
  while i <= len do
    local row, blank = { line = line }, true
    while true do
      local field
      if text:byte(i) == 34 then                 -- "..."
        local parts, j, qline = {}, i + 1, line
        while true do
          local q = text:find('"', j, true)
          if q == nil then
            fail(qline, format("field %d: the quote that opens it is not closed", #row + 1))
          end
          local piece = text:sub(j, q - 1)
          parts[#parts + 1] = piece
          line = line + select(2, piece:gsub("\n", ""))
          if text:byte(q + 1) == 34 then
            parts[#parts + 1] = '"'
            j = q + 2
          else
            i = q + 1
            break
          end
        end
        field, blank = table.concat(parts), false
        local c = text:sub(i, i)
        if c ~= "," and c ~= "\n" and c ~= "\r" and c ~= "" then
          local after = text:match("^[ \t]*", i)
          i = i + #after
          c = text:sub(i, i)
          if c ~= "," and c ~= "\n" and c ~= "\r" and c ~= "" then
            fail(line, format("field %d: text after the closing quote (a quote inside a "
              .. "field is written twice: \"a \"\"b\"\" c\")", #row + 1))
          end
        end
      else
        local j = text:find('[,\r\n"]', i) or len + 1
        if text:byte(j) == 34 then
          fail(line, format("field %d: a quote inside an unquoted field (put the field in "
            .. "quotes and write the quote twice: \"a \"\"b\"\" c\")", #row + 1))
        end
        field = text:sub(i, j - 1):match("^[ \t]*(.-)[ \t]*$")
        if field ~= "" then blank = false end
        i = j
      end
      row[#row + 1] = field
      local c = text:sub(i, i)
      if c == "," then
        i, blank = i + 1, false
      else
        if c == "\r" then i = i + (text:sub(i + 1, i + 1) == "\n" and 2 or 1)
        elseif c == "\n" then i = i + 1 end
        if c ~= "" then line = line + 1 end
        break
      end
    end
    if not blank then return row, i, line end
  end
  return nil, i, line
end

-- Where the records of CSV text begin: byte 4 after a UTF-8 byte order mark, else 1.
local function csv_start (text)
  return text:sub(1, 3) == "\239\187\191" and 4 or 1
end

--[[
Parses the CSV text `text` of the file `name`: fields separated by commas, records by CRLF
or LF; a field in double quotes may hold commas, line breaks and quotes written twice ("").
Spaces around an unquoted field are dropped; a UTF-8 byte order mark at the start is
skipped; empty lines are skipped. Returns the records, each a list of fields with `line`, the
line it begins on. Raises "name:line: ..." for a quote left open (the line it opens on), text
after a closing quote, and a quote inside an unquoted field.
]]
function M.csv (text, name)
  if type(text) ~= "string" or type(name) ~= "string" then
    error("lsys.batch.csv: the text and the file's name must be strings", 2)
  end
  local rows, i, line = {}, csv_start(text), 1
  while true do
    local row
    row, i, line = csv_record(text, i, line, name)
    if row == nil then return rows end
    rows[#rows + 1] = row
  end
end

M.record, M.start = csv_record, csv_start

return M
