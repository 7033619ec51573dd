// The first of equivalent items, each compared only with the earlier items of its key: a sort, not all pairs, for a
// scene of thousands of materials (dedup's equal materials, the join's groups by base colour).
#pragma once

#include <map>
#include <optional>
#include <type_traits>
#include <vector>

namespace symcompress {

// For each of `count` items, the first item equivalent to it (`equivalent(earlier, item)`), itself when none is
// earlier. Only items of equal keys (`keyOf(item)`, a std::optional) are compared; an item without a key is
// equivalent to none.
template <typename KeyOf, typename Equivalent>
std::vector<int> firstEquivalent(std::size_t count, KeyOf keyOf, Equivalent equivalent) {
    using Key = typename std::invoke_result_t<KeyOf, std::size_t>::value_type;
    std::map<Key, std::vector<int>> byKey;
    std::vector<int> first(count);
    for (std::size_t i = 0; i < count; ++i) {
        first[i] = int(i);
        const auto key = keyOf(i);
        if (!key) continue;
        std::vector<int>& candidates = byKey[*key];
        for (int c : candidates)
            if (equivalent(std::size_t(c), i)) {
                first[i] = c;
                break;
            }
        if (first[i] == int(i)) candidates.push_back(int(i));
    }
    return first;
}

}  // namespace symcompress
