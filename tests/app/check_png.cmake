# Checks that FILE starts with the PNG signature (89 50 4E 47 0D 0A 1A 0A).
file(READ ${FILE} head LIMIT 8 HEX)
if(NOT head STREQUAL "89504e470d0a1a0a")
  message(FATAL_ERROR "${FILE} is not a PNG (first bytes ${head})")
endif()
