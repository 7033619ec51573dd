// meshoptimizer's vertex codec as KHR_meshopt_compression specifies it (Appendix A, mode 0), versions 0 and 1,
// and its colour filter (Appendix B, filter 4): what the packaged libmeshoptimizer (0.18) lacks, version 1
// being newer. EXT_meshopt_compression's streams are version 0, which that library decodes.
#pragma once

#include <cstddef>

namespace symcompress {

// Decodes `size` bytes of a vertex stream (header byte 0xa0 or 0xa1) into `count` elements of `stride` bytes
// (a multiple of 4, at most 256) at `out`. False, `out` partly written, where the stream is not one: a wrong
// header, too short, bytes left over before its tail, a channel mode the specification does not define.
bool decodeMeshoptVertexStream(unsigned char* out, std::size_t count, std::size_t stride, const unsigned char* data,
                               std::size_t size);

// The colour filter, in place over `count` elements of `stride` bytes (4: 8-bit components, 8: 16-bit): YCoCg
// with an alpha that says the bits used, to RGBA normalized integers.
void decodeMeshoptColorFilter(unsigned char* data, std::size_t count, std::size_t stride);

}  // namespace symcompress
