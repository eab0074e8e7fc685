# Reports functions longer than MAX lines: a body opens with "{" at the end of a line at column 0 depth
# (C: "{" alone on a line after the signature; GLSL: "... ) {" or "{" alone) and closes at depth 0.
function count(s, ch,   n) { n = gsub(ch, "", s); return n }
FNR == 1 { depth = 0; infn = 0; prev = "" }
{
  line = $0
  sub(/\/\/.*/, "", line)
  gsub(/"([^"\\]|\\.)*"/, "\"\"", line)
  gsub(/'([^'\\]|\\.)*'/, "''", line)
  o = count(line, "{"); c = count(line, "}")
  if (depth == 0 && o > 0) {
    # a function if the text before the brace (this line or the last non-blank) ends with ")"
    head = line; sub(/\{.*/, "", head)
    if (head ~ /\)[ \t]*(const)?[ \t]*$/ || (head ~ /^[ \t]*$/ && prev ~ /\)[ \t]*$/)) { start = FNR; name = (head ~ /^[ \t]*$/ ? prev : head); infn = 1 }
  }
  depth += o - c
  if (infn && depth == 0) { len = FNR - start + 1; if (len > MAX) printf "%s:%d: %d lines: %s\n", FILENAME, start, len, name; infn = 0 }
  if (line !~ /^[ \t]*$/) prev = line
}
