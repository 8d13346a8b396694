#pragma once

namespace igi {

// The identity of this build: the project version and `git describe --dirty` of the tree it was
// built from. Master and clients exchange it at connect and refuse a mismatch. Defined in a file
// generated before every build (cmake/BuildId.cmake) rather than as a compile definition, which
// made every commit recompile the whole project.
const char* buildId();

}  // namespace igi
