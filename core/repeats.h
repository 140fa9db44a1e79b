#pragma once
// One rule for every list a program takes (resolutions, budgets, levels, radii, technique
// specs): each value once, compared AS PARSED. "64,064", "4,4.0" and "csm:pcf=3,csm:pcf=03" name
// one value twice; a run would compute it twice and its outputs would overwrite each other.
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/parse_number.h"

namespace shadowlab {

// Throws InputError(flag, …) at the first item equal (by `same`) to an earlier one; `text(i)`
// is item i as the user wrote it, named in the message.
template <class T, class Same, class Text>
void reject_repeats(const std::string& flag, const std::vector<T>& items, Same same, Text text) {
  for (size_t i = 0; i < items.size(); ++i)
    for (size_t j = 0; j < i; ++j) {
      if (!same(items[j], items[i])) continue;
      const std::string a = text(j), b = text(i);
      throw InputError(flag, (a == b ? "'" + a + "'" : "'" + b + "' (the same as '" + a + "')") +
                                 " given twice (a list names each value once, compared as parsed)");
    }
}

// Numbers compared with ==; `texts` as written (same size as `items`), else the values' text.
template <class T>
void reject_repeats(const std::string& flag, const std::vector<T>& items,
                    const std::vector<std::string>& texts = {}) {
  reject_repeats(
      flag, items, [](const T& a, const T& b) { return a == b; },
      [&](size_t i) {
        if (i < texts.size()) return texts[i];
        if constexpr (std::is_floating_point_v<T>) return number_text(double(items[i]));
        else return std::to_string(items[i]);
      });
}

}  // namespace shadowlab
