# Writes the file IN as a C++ raw string literal into OUT (master/ViewPage.cpp includes it).
file(READ "${IN}" content)
file(WRITE "${OUT}.tmp" "R\"igiview(${content})igiview\"\n")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
