#pragma once

#include <optional>
#include <string>
#include <vector>

namespace igi {

/// The known key an unknown one was probably meant to be, for "did you mean" in messages: a
/// known name for the same thing ("spp" -> "path_samples"), the key with underscores for
/// dashes or in lower case ("direct-samples" -> "direct_samples"), or the one key within a
/// small edit distance ("transfrom" -> "transform"). None when nothing is close, or when two
/// keys are equally close.
std::optional<std::string> suggestKey(const std::string& unknown,
                                      const std::vector<std::string>& known);

/// " (did you mean 'transform'?)" for an unknown key with a suggestion; else empty.
std::string didYouMean(const std::string& unknown, const std::vector<std::string>& known);

}  // namespace igi
