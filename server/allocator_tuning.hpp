// How the scene parser worker process keeps freed memory: it parses one scene after another and
// does nothing else. With glibc's defaults the large blocks of one scene are mapped and unmapped
// each time, and the next scene faults its pages in again: on the 2-core VM, cold thumbnails
// spent a third of the parser's time in the kernel (docs/BENCHMARKS.md). Freed memory up to the
// trim threshold stays in the process for the next scene; RLIMIT_DATA, and so
// --scene-worker-memory-mb, still counts it. Not for lghd's own process: its many threads'
// arenas each kept their freed blocks, and its resident memory crept by up to 8 % in the short
// soak under load.
#pragma once

namespace lgh {

// Call once, at the start of main(), before the threads start.
void keepFreedMemoryForReuse();

}  // namespace lgh
