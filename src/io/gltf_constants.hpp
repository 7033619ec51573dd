// glTF's numbers for component types, buffer view targets and primitive modes.
#pragma once

namespace symcompress {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kModePoints = 0, kModeLines = 1;  // a primitive's mode (TRIANGLES, 4, is the default)
// An accessor without a buffer view is zeros (glTF 2.0, 3.6.2.1): the reader makes up to this many bytes of
// them, or as many as the file's buffers hold, so that a small file cannot ask for gigabytes.
constexpr unsigned long long kMostZeroBytes = 1ull << 26;

// The bytes of one component of `componentType`.
constexpr int componentBytes(int componentType) {
    return componentType == kByte || componentType == kUnsignedByte     ? 1
           : componentType == kShort || componentType == kUnsignedShort ? 2
                                                                        : 4;
}

}  // namespace symcompress
