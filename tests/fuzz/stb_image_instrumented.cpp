// stb_image's decoders compiled with this build's flags, so that the sanitizers
// and the fuzzer's coverage see inside them: Debian's prebuilt libstb.a (which
// src/ links) is not instrumented, and UB in its decoders would go unseen. The
// executables of tests/fuzz take stb_image from here (the same header version
// as libstb.a; see _fuzz_link in CMakeLists.txt). Remove once src/image no
// longer decodes through stb.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
