#include "scene/KeySuggestion.h"

#include <algorithm>
#include <cctype>
#include <utility>
#include <vector>

namespace igi {
namespace {

// Other programs' names for keys of ours (the command line's among them), which no edit
// distance finds.
const std::pair<const char*, const char*> kSynonyms[] = {
    {"spp", "path_samples"}, {"samples", "path_samples"}, {"samples_per_pixel", "path_samples"},
    {"fov", "fov_y"},        {"target", "look_at"},       {"lookat", "look_at"},
    {"eye", "position"},
};

// "Direct-Samples" -> "direct_samples".
std::string normalized(const std::string& key) {
    std::string out = key;
    for (char& c : out) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (c == '-' || c == ' ') c = '_';
    }
    return out;
}

// Levenshtein distance, with a swap of neighbours counted as one edit ("transfrom").
std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1,
                                d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

bool isKnown(const std::string& key, const std::vector<std::string>& known) {
    return std::find(known.begin(), known.end(), key) != known.end();
}

}  // namespace

std::optional<std::string> suggestKey(const std::string& unknown,
                                      const std::vector<std::string>& known) {
    const std::string key = normalized(unknown);
    if (isKnown(key, known)) return key;
    for (const auto& [alias, target] : kSynonyms)
        if (key == alias && isKnown(target, known)) return std::string(target);
    // Close enough to be a typo: a third of the key's letters, and at least one.
    const std::size_t limit = std::max<std::size_t>(1, key.size() / 3);
    std::optional<std::string> best;
    std::size_t bestDistance = limit + 1;
    bool tie = false;
    for (const std::string& k : known) {
        const std::size_t d = editDistance(key, k);
        if (d < bestDistance) {
            best = k;
            bestDistance = d;
            tie = false;
        } else if (d == bestDistance) {
            tie = true;
        }
    }
    if (tie || bestDistance > limit) return std::nullopt;
    return best;
}

std::string didYouMean(const std::string& unknown, const std::vector<std::string>& known) {
    const std::optional<std::string> key = suggestKey(unknown, known);
    return key ? "; did you mean '" + *key + "'?" : "";
}

}  // namespace igi
