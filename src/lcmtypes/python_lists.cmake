# Makes lcm-gen's Python types decode arrays to lists (cmake -P, run after `lcm-gen -p`).
# Debian 12's lcm-gen 1.3.1 decodes a boolean array to map(bool, ...), a one-shot iterator that
# cannot be indexed and that encode() cannot slice, and other arrays to tuples; the
# rewritten decoders return lists, which index, compare and re-encode like any Python sequence.
#   cmake -DPY_FILES="a.py;b.py" -P python_lists.cmake
foreach(py ${PY_FILES})
  file(READ ${py} code)
  # self.x = map(bool, struct.unpack(...))  ->  self.x = list(map(bool, struct.unpack(...)))
  string(REGEX REPLACE "= map\\(bool, (struct\\.unpack\\([^\n]*\\))\\)\n" "= list(map(bool, \\1))\n"
    code "${code}")
  # self.x = struct.unpack('>%dd' % n, ...)  ->  self.x = list(struct.unpack(...)) (arrays only)
  string(REGEX REPLACE "= (struct\\.unpack\\('>%d[^\n]*\\))\n" "= list(\\1)\n" code "${code}")
  file(WRITE ${py} "${code}")
endforeach()
