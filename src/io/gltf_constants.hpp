// glTF's numbers for component types, buffer view targets and primitive modes.
#pragma once

namespace symcompress {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kModePoints = 0, kModeLines = 1;  // a primitive's mode (TRIANGLES, 4, is the default)

// The bytes of one component of `componentType`.
constexpr int componentBytes(int componentType) {
    return componentType == kByte || componentType == kUnsignedByte     ? 1
           : componentType == kShort || componentType == kUnsignedShort ? 2
                                                                        : 4;
}

}  // namespace symcompress
