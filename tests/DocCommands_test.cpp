// Every command the README and docs/ show runs as written from the repository root, after the
// README's first command (scripts/run.sh) has built build/bin/. The tests read README.md,
// docs/*.md and deploy/README.md:
// - EveryCommandIsRunOrSkippedForAStatedReason: the command lines of their shell code blocks
//   (tagged sh, or untagged and starting with build/bin/ or scripts/; backslash continuations
//   joined, comments dropped) are each either run or on the skip list below with its reason. A
//   line the test does not recognise fails it, so a new command in a document cannot escape.
// - SingleMachineExamplesRunAsWritten: runs them, with fewer frames and a small image.
// - ProseNamesOnlyExistingFlagsAndScripts: every inline code span that starts with one of the
//   executables (`igi-master --foo`, `igi-ctl object ... --bar`) names only flags of its --help
//   (of the subcommand's --help for igi-ctl), a span of flags alone (`--reconnect-seconds`)
//   only flags some executable or script has, a script (`scripts/x.sh --flag`) exists and
//   handles the flag; the code blocks' commands, skipped ones included, are checked the same.
//
// How a block runs. Each block gets a fresh copy of the repository root's layout in a scratch
// folder: a symbolic link to every top-level entry of the source tree (scenes/, master/,
// scripts/, ...), except build*, out/ and .git, plus build/bin -> the executables under test.
// The commands run there, unchanged, with that folder as their working directory, as the shell
// would run them: `build/bin/igi-master --scene scenes/cornell/cornell.json ... --output
// out/image.png` writes out/image.png inside the scratch folder, never into the source tree's
// out/ (the logs go beside it, not into it). What is changed, and why:
// - `--frames N` (N > 0) becomes --frames 2, and igi-master gets --width 160 --height 120 unless
//   the command gives a size: a few seconds per command on a shared 2-core machine.
// - Fixed ports (7878, 7879) become free ones, the same one for every mention in a block, so
//   that the test never collides with another run; 0.0.0.0 and MASTER_HOST become 127.0.0.1.
//   Commands written for several hosts run on loopback: the master in the background, then as
//   many `igi-client` copies as the master's --clients says, each with --threads 1.
// - A master with --frames 0 (until stopped) or --clients N runs in the background; the block's
//   igi-ctl lines run against it once its control port answers `igi-ctl status`, and the block
//   must stop it (`igi-ctl ... stop`) or it must finish its frames. It must exit with code 0,
//   and so must its clients.
// - Shell lines (pipes, redirections) run through /bin/sh in the scratch folder, and only the
//   known one (making the cluster secret); any other shell line fails the test.
// Each command must exit with code 0, and what it names as output (--output, --output-sequence,
// --stats-json, `igi-ctl snapshot FILE`) must exist afterwards: images are read back and must be
// non-empty with finite pixels, statistics must parse as JSON with one entry per frame.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Session.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

/// The frame count every `--frames N` (N > 0) is reduced to, and the image size added.
constexpr int kFrames = 2;
const char* const kWidth = "160";
const char* const kHeight = "120";
/// igi-master's default --frames (its --help: `--frames ... =1`).
constexpr int kMasterDefaultFrames = 1;

/// The project's executables, as docs name them.
const std::set<std::string> kBinaries = {"igi-master",  "igi-client", "igi-ctl",
                                         "igi-compare", "igi-bench",  "igi-codec-bench"};

/// Commands of the documents that are not run, and why. A rule applies to the commands of
/// `file` (any document if empty) whose text (comment removed) matches `pattern`.
struct SkipRule {
    std::string file;
    std::regex pattern;
    std::string reason;
};

const std::vector<SkipRule>& skipRules() {
    static const std::vector<SkipRule> rules = {
        {"", std::regex(R"(^scripts/run\.sh(\s|$))"),
         "the README's first command: installs packages and builds build/, which this test "
         "takes as done (it runs from that build); scripts/fresh_machine_check.sh runs it on "
         "a fresh Debian root"},
        {"", std::regex(R"(^scripts/test\.sh(\s|$))"),
         "the test command: it runs this test and cannot run itself; "
         "scripts/fresh_machine_check.sh runs it on a fresh Debian root"},
        {"", std::regex(R"(^(sudo )?scripts/fresh_machine_check\.sh(\s|$))"),
         "both README commands on a new debootstrapped Debian root: root only, 20-40 minutes"},
        {"", std::regex(R"(^(FUZZ_TARGETS=\S+ )?scripts/fuzz\.sh(\s|$))"),
         "a long libFuzzer run (600 s per target by default; the test command runs short ones)"},
        {"", std::regex(R"(^(IGI_BUILD=\S+ )?scripts/bench_[a-z_]+\.sh(\s|$))"),
         "a benchmark of several minutes that rewrites docs/ (PERFORMANCE.md, ACCURACY.md)"},
        {"", std::regex(R"(^scripts/equal_time\.py(\s|$))"),
         "a table over a benchmark's committed results.csv (docs/accuracy/*/): no renderer "
         "runs, and what it prints is quoted in the document beside it"},
        {"", std::regex(R"(^scripts/cluster\.sh(\s|$))"),
         "needs ssh hosts; tests/Cluster_test.cpp runs it against real sshd servers on test "
         "hosts made of network namespaces"},
        {"", std::regex(R"(^sbatch\s)"),
         "needs a SLURM cluster; tests/Slurm_test.cpp submits deploy/slurm/igi.sbatch to a "
         "one-machine SLURM that it starts"},
        {"", std::regex(R"(^scripts/fault_injection\.sh(\s|$))"),
         "minutes of random kills and stops against running sessions"},
        {"", std::regex(R"(^(IGI_BUILD=\S+ )?(nice -n \d+ )?scripts/soak\.sh(\s|$))"),
         "a live session of --minutes M (10 by default, 60 for the recorded run) with random "
         "changes, faults and a browser; tests/LongSession_test.cpp is its short version"},
        {"docs/FUZZING.md", std::regex(R"(^(CC=clang CXX=clang\+\+ )?cmake\s)"),
         "the clang fuzz build: what the test command (scripts/test.sh) does itself, many "
         "minutes on 2 cores"},
        {"docs/FUZZING.md", std::regex(R"(^ctest\s)"),
         "the fuzz build's short runs: what the test command (scripts/test.sh) runs itself"},
    };
    return rules;
}

/// The one shell line the documents may show, run as written: making the cluster secret.
const std::regex kSecretLine(R"(^head -c \d+ /dev/urandom \| base64 > (\S+) && chmod 600 (\S+)$)");

// ---------------------------------------------------------------------------------------------
// Reading the documents

struct Document {
    std::string name;  ///< relative to the repository root, e.g. "docs/ANIMATION.md"
    std::vector<std::string> lines;
};

std::vector<Document> documents() {
    std::vector<fs::path> paths = {sourceDir() / "README.md"};
    std::vector<fs::path> docs;
    for (const auto& entry : fs::directory_iterator(sourceDir() / "docs"))
        if (entry.path().extension() == ".md") docs.push_back(entry.path());
    std::sort(docs.begin(), docs.end());
    paths.insert(paths.end(), docs.begin(), docs.end());
    if (fs::exists(sourceDir() / "deploy" / "README.md"))
        paths.push_back(sourceDir() / "deploy" / "README.md");
    std::vector<Document> result;
    for (const auto& path : paths) {
        Document d{fs::relative(path, sourceDir()).generic_string(), {}};
        std::istringstream text(readFile(path));
        for (std::string line; std::getline(text, line);) d.lines.push_back(line);
        result.push_back(std::move(d));
    }
    return result;
}

/// A command line of a code block: continuation lines joined, comment removed.
struct Command {
    std::string file;
    int line = 0;                    ///< 1-based, of its first line
    std::string text;                ///< the command as the shell reads it, without the comment
    std::vector<std::string> words;  ///< split as the shell splits it (quotes removed)
    bool shellSyntax = false;        ///< has pipes, redirections, `&&`, `$`, ...
    std::string where() const { return file + ":" + std::to_string(line); }
};

struct Block {
    std::string file;
    int line = 0;
    std::vector<Command> commands;
};

struct Words {
    std::vector<std::string> words;
    std::string code;  ///< the text before a comment, trimmed
    bool shellSyntax = false;
};

/// Splits a line as a POSIX shell would into words (quotes and backslashes), up to a comment.
Words shellWords(const std::string& line) {
    Words w;
    std::string word;
    bool inWord = false;
    char quote = 0;
    std::size_t end = line.size();
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quote) {
            if (c == quote)
                quote = 0;
            else if (quote == '"' && c == '\\' && i + 1 < line.size())
                word += line[++i];
            else
                word += c;
            continue;
        }
        if (c == '\'' || c == '"') {
            quote = c;
            inWord = true;
        } else if (c == '\\' && i + 1 < line.size()) {
            word += line[++i];
            inWord = true;
        } else if (c == ' ' || c == '\t') {
            if (inWord) w.words.push_back(word), word.clear(), inWord = false;
        } else if (c == '#' && !inWord) {
            end = i;
            break;
        } else {
            if (std::string("|&;<>()$`").find(c) != std::string::npos) w.shellSyntax = true;
            word += c;
            inWord = true;
        }
    }
    if (inWord) w.words.push_back(word);
    w.code = line.substr(0, end);
    w.code.erase(0, w.code.find_first_not_of(" \t"));
    w.code.erase(w.code.find_last_not_of(" \t") + 1);
    return w;
}

/// Leading `NAME=value` words (environment assignments) are not the command.
std::size_t commandStart(const std::vector<std::string>& words) {
    static const std::regex assignment(R"(^[A-Za-z_][A-Za-z0-9_]*=.*)");
    std::size_t i = 0;
    while (i < words.size() && std::regex_match(words[i], assignment)) ++i;
    return i;
}

/// The fenced code blocks of a document that hold commands: tagged sh (bash, shell), or untagged
/// with a line that starts with build/bin/ or scripts/. Also returns, through `prose`, the
/// document with every fenced block blanked out (for the inline code spans).
std::vector<Block> commandBlocks(const Document& doc, std::vector<std::string>* prose = nullptr) {
    static const std::regex open(R"(^\s*(```+)\s*([A-Za-z0-9_+-]*).*$)");
    std::vector<Block> blocks;
    if (prose) *prose = doc.lines;
    for (std::size_t i = 0; i < doc.lines.size(); ++i) {
        std::smatch m;
        if (!std::regex_match(doc.lines[i], m, open)) continue;
        const std::size_t fence = m[1].length();
        const std::string tag = m[2].str();
        const std::size_t first = i + 1;
        std::size_t last = first;
        while (last < doc.lines.size()) {
            static const std::regex close(R"(^\s*(```+)\s*$)");
            std::smatch c;
            if (std::regex_match(doc.lines[last], c, close) && std::size_t(c[1].length()) >= fence)
                break;
            ++last;
        }
        if (prose)
            for (std::size_t k = i; k <= std::min(last, doc.lines.size() - 1); ++k)
                (*prose)[k].clear();
        const bool shell = tag == "sh" || tag == "bash" || tag == "shell";
        bool looksLikeCommands = false;
        if (tag.empty())
            for (std::size_t k = first; k < last; ++k) {
                const auto words = shellWords(doc.lines[k]).words;
                const std::size_t s = commandStart(words);
                if (s < words.size() &&
                    (words[s].rfind("build/bin/", 0) == 0 || words[s].rfind("scripts/", 0) == 0))
                    looksLikeCommands = true;
            }
        if (shell || looksLikeCommands) {
            Block block{doc.name, int(i) + 1, {}};
            for (std::size_t k = first; k < last; ++k) {
                Command command{doc.name, int(k) + 1, "", {}, false};
                std::string joined = doc.lines[k];
                // A backslash at the end of a line continues the command on the next one.
                while (!joined.empty() && joined.back() == '\\' && k + 1 < last) {
                    const std::string& next = doc.lines[++k];
                    joined.pop_back();
                    joined +=
                        " " + next.substr(std::min(next.size(), next.find_first_not_of(" \t")));
                }
                const Words w = shellWords(joined);
                if (w.words.empty()) continue;  // blank or a comment
                command.text = w.code;
                command.words = w.words;
                command.shellSyntax = w.shellSyntax;
                block.commands.push_back(std::move(command));
            }
            blocks.push_back(std::move(block));
        }
        i = last;
    }
    return blocks;
}

/// An inline code span of a document's prose.
struct Span {
    std::string file;
    int line = 0;
    std::string text;  ///< whitespace (line breaks included) collapsed to single spaces
};

/// The inline code spans outside fenced blocks: `...` and ``...``, which may run over a line
/// break inside a paragraph.
std::vector<Span> inlineSpans(const Document& doc) {
    std::vector<std::string> prose;
    commandBlocks(doc, &prose);
    std::vector<Span> spans;
    // Paragraphs: a blank line ends a span that was not closed (a stray backtick).
    std::size_t i = 0;
    while (i < prose.size()) {
        while (i < prose.size() && prose[i].find_first_not_of(" \t") == std::string::npos) ++i;
        const std::size_t start = i;
        std::string text;
        std::vector<int> lineOf;  // source line of each character
        while (i < prose.size() && prose[i].find_first_not_of(" \t") != std::string::npos) {
            text += prose[i] + "\n";
            lineOf.insert(lineOf.end(), prose[i].size() + 1, int(i) + 1);
            ++i;
        }
        if (start == i) break;
        for (std::size_t p = 0; p < text.size();) {
            if (text[p] != '`') {
                ++p;
                continue;
            }
            std::size_t run = text.find_first_not_of('`', p);
            if (run == std::string::npos) break;
            const std::size_t ticks = run - p;
            // The closing run has exactly as many backticks.
            std::size_t q = run, close = std::string::npos;
            while ((q = text.find('`', q)) != std::string::npos) {
                const std::size_t e = std::min(text.find_first_not_of('`', q), text.size());
                if (e - q == ticks) {
                    close = q;
                    break;
                }
                q = e;
            }
            if (close == std::string::npos) {
                p = run;
                continue;
            }
            std::string content = text.substr(run, close - run);
            std::replace(content.begin(), content.end(), '\n', ' ');
            content = std::regex_replace(content, std::regex(R"(\s+)"), " ");
            content.erase(0, content.find_first_not_of(' '));
            content.erase(content.find_last_not_of(' ') + 1);
            spans.push_back({doc.name, lineOf[p], content});
            p = close + ticks;
        }
    }
    return spans;
}

// ---------------------------------------------------------------------------------------------
// What a command is

enum class Kind { Skip, Secret, Master, Client, Ctl, Tool, Unknown };

struct Classified {
    Kind kind = Kind::Unknown;
    std::string binary;  ///< for executables: "igi-master", ...
    std::string reason;  ///< for Skip: why; for Unknown: what is wrong
};

Classified classify(const Command& command) {
    for (const auto& rule : skipRules())
        if ((rule.file.empty() || rule.file == command.file) &&
            std::regex_search(command.text, rule.pattern))
            return {Kind::Skip, "", rule.reason};
    if (std::regex_match(command.text, kSecretLine)) return {Kind::Secret, "", ""};
    if (command.shellSyntax)
        return {Kind::Unknown, "",
                "a shell line (pipe, redirection, `&&`, `$`, ...) that the test does not know"};
    const std::size_t s = commandStart(command.words);
    if (s != 0 || command.words.empty())
        return {Kind::Unknown, "", "environment assignments before a command"};
    static const std::regex executable(R"(^build/bin/([a-z-]+)$)");
    std::smatch m;
    if (!std::regex_match(command.words[0], m, executable)) {
        const std::string name = fs::path(command.words[0]).filename().string();
        if (kBinaries.count(name))
            return {Kind::Unknown, "",
                    "names " + command.words[0] +
                        ": from the repository root the executables are build/bin/" + name};
        return {Kind::Unknown, "", "not one of the project's commands, and not on the skip list"};
    }
    const std::string binary = m[1].str();
    if (!kBinaries.count(binary))
        return {Kind::Unknown, "", "build/bin/" + binary + " is not one of the executables"};
    if (binary == "igi-master") return {Kind::Master, binary, ""};
    if (binary == "igi-client") return {Kind::Client, binary, ""};
    if (binary == "igi-ctl") return {Kind::Ctl, binary, ""};
    return {Kind::Tool, binary, ""};
}

/// The value after `flag` (or in `flag=value`); empty if the flag is absent.
std::optional<std::string> flagValue(const std::vector<std::string>& words,
                                     const std::string& flag) {
    for (std::size_t i = 0; i < words.size(); ++i) {
        if (words[i] == flag && i + 1 < words.size()) return words[i + 1];
        if (words[i].rfind(flag + "=", 0) == 0) return words[i].substr(flag.size() + 1);
    }
    return std::nullopt;
}

/// Every value of a repeatable option that takes several values (`--output a.png b.exr`).
std::vector<std::string> flagValues(const std::vector<std::string>& words,
                                    const std::string& flag) {
    std::vector<std::string> values;
    for (std::size_t i = 0; i < words.size(); ++i) {
        if (words[i].rfind(flag + "=", 0) == 0) values.push_back(words[i].substr(flag.size() + 1));
        if (words[i] != flag) continue;
        for (std::size_t k = i + 1; k < words.size() && words[k].rfind("--", 0) != 0; ++k)
            values.push_back(words[k]);
    }
    return values;
}

bool hasFlag(const std::vector<std::string>& words, const std::string& flag) {
    for (const auto& w : words)
        if (w == flag || w.rfind(flag + "=", 0) == 0) return true;
    return false;
}

/// Sets a flag's value, or appends the flag.
void setFlag(std::vector<std::string>& words, const std::string& flag, const std::string& value) {
    for (std::size_t i = 0; i < words.size(); ++i) {
        if (words[i] == flag && i + 1 < words.size()) {
            words[i + 1] = value;
            return;
        }
        if (words[i].rfind(flag + "=", 0) == 0) {
            words[i] = flag + "=" + value;
            return;
        }
    }
    words.push_back(flag);
    words.push_back(value);
}

int intFlag(const std::vector<std::string>& words, const std::string& flag, int otherwise) {
    const auto value = flagValue(words, flag);
    if (!value) return otherwise;
    try {
        return std::stoi(*value);
    } catch (const std::exception&) {
        return otherwise;
    }
}

// ---------------------------------------------------------------------------------------------
// The executables' --help, for the flags the documents name

class Help {
  public:
    /// The long flags of `binary` (and of its subcommand `sub`, if not empty).
    const std::set<std::string>& flags(const std::string& binary, const std::string& sub = "") {
        load(binary, sub);
        return flags_[key(binary, sub)];
    }
    const std::set<std::string>& subcommands(const std::string& binary) {
        load(binary, "");
        return subcommands_[binary];
    }
    const std::string& text(const std::string& binary, const std::string& sub = "") {
        load(binary, sub);
        return text_[key(binary, sub)];
    }

  private:
    static std::string key(const std::string& binary, const std::string& sub) {
        return sub.empty() ? binary : binary + " " + sub;
    }
    void load(const std::string& binary, const std::string& sub) {
        const std::string k = key(binary, sub);
        if (text_.count(k)) return;
        std::vector<std::string> command = {(binDir() / binary).string()};
        if (!sub.empty()) command.push_back(sub);
        command.push_back("--help");
        const fs::path dir = scratchDir("doc-help");
        const ProcessResult r = runProcess(command, dir / "help.log", 60);
        fs::remove_all(dir);
        EXPECT_EQ(r.exitCode, 0) << k << " --help:\n" << r.output;
        text_[k] = r.output;
        static const std::regex option(R"(^\s+(?:-[A-Za-z0-9],)?(--[A-Za-z0-9][A-Za-z0-9-]*))");
        static const std::regex subcommand(R"(^  ([a-z][a-z0-9-]*)\s)");
        std::istringstream lines(r.output);
        bool inSubcommands = false;
        for (std::string line; std::getline(lines, line);) {
            std::smatch m;
            if (line.rfind("Subcommands:", 0) == 0)
                inSubcommands = true;
            else if (!line.empty() && line[0] != ' ')
                inSubcommands = false;
            if (inSubcommands && sub.empty() && std::regex_search(line, m, subcommand))
                subcommands_[binary].insert(m[1].str());
            else if (std::regex_search(line, m, option))
                flags_[k].insert(m[1].str());
        }
    }
    std::map<std::string, std::string> text_;
    std::map<std::string, std::set<std::string>> flags_;
    std::map<std::string, std::set<std::string>> subcommands_;
};

Help& help() {
    static Help h;
    return h;
}

/// The long flags a command (or a fragment of one in prose: `[--rounds N]`) names.
std::vector<std::string> namedFlags(const std::vector<std::string>& words, std::size_t from = 0) {
    static const std::regex flag(R"(^\[?(--[A-Za-z0-9][A-Za-z0-9-]*))");
    std::vector<std::string> flags;
    for (std::size_t i = from; i < words.size(); ++i) {
        std::smatch m;
        if (std::regex_search(words[i], m, flag)) flags.push_back(m[1].str());
    }
    return flags;
}

/// A command of one of the executables names only flags its --help lists; igi-ctl's flags after
/// a subcommand are that subcommand's. The files it names in the repository exist.
void expectKnownFlags(const std::string& where, const std::string& shown,
                      const std::vector<std::string>& words) {
    const std::string binary = fs::path(words[0]).filename().string();
    if (!fs::exists(binDir() / binary)) {
        ADD_FAILURE() << where << ": `" << shown << "`: there is no executable " << binary;
        return;
    }
    std::string sub;
    static const std::regex flag(R"(^\[?(--[A-Za-z0-9][A-Za-z0-9-]*))");
    static const std::regex repositoryFile(
        R"(^(scenes|master|scripts|docs|deploy|fuzz|tests|tools|common)/[^ ]*\.[A-Za-z0-9]+$)");
    for (std::size_t i = 1; i < words.size(); ++i) {
        std::smatch m;
        if (std::regex_search(words[i], m, flag)) {
            const std::string name = m[1].str();
            if (!help().flags(binary, sub).count(name))
                ADD_FAILURE() << where << ": `" << shown << "` names " << name << ", which `"
                              << binary << (sub.empty() ? "" : " " + sub)
                              << " --help` does not list:\n"
                              << help().text(binary, sub);
        } else if (sub.empty() && help().subcommands(binary).count(words[i])) {
            sub = words[i];
        } else if (std::regex_match(words[i], repositoryFile) &&
                   !fs::exists(sourceDir() / words[i])) {
            ADD_FAILURE() << where << ": `" << shown << "` names " << words[i]
                          << ", which the repository does not have";
        }
    }
}

/// A script a document names exists, and every flag it is shown with appears in its text. What
/// follows a bare `--` is the master's (scripts/cluster.sh passes it on): igi-master's flags.
void expectScriptFlags(const std::string& where, const std::string& shown,
                       std::vector<std::string> words) {
    const std::size_t s = commandStart(words);
    if (s >= words.size()) return;
    const fs::path script = sourceDir() / words[s];
    if (!fs::is_regular_file(script)) {
        ADD_FAILURE() << where << ": `" << shown << "`: there is no " << words[s];
        return;
    }
    const auto dashes = std::find(words.begin() + std::ptrdiff_t(s), words.end(), "--");
    if (dashes != words.end()) {
        std::vector<std::string> master = {"igi-master"};
        master.insert(master.end(), dashes + 1, words.end());
        expectKnownFlags(where, shown, master);
        words.erase(dashes, words.end());
    }
    const std::string text = readFile(script);
    for (const auto& flag : namedFlags(words, s + 1))
        if (!std::regex_search(text, std::regex(flag + R"((\s|\)|\||"|=|$))")))
            ADD_FAILURE() << where << ": `" << shown << "` names " << flag << ", which " << words[s]
                          << " does not handle";
    for (std::size_t i = 0; i < s; ++i) {
        const std::string variable = words[i].substr(0, words[i].find('='));
        if (text.find(variable) == std::string::npos)
            ADD_FAILURE() << where << ": `" << shown << "` sets " << variable << ", which "
                          << words[s] << " does not read";
    }
}

// ---------------------------------------------------------------------------------------------
// Running commands from a scratch copy of the repository root

/// Starts a process in `cwd` (a relative argv[0] is found from there, as the shell would),
/// its output going to `log`.
pid_t spawnIn(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
    std::vector<std::string> copy = args;
    std::vector<char*> argv;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid = -1;
    posix_spawn_file_actions_destroy(&actions);
    return pid;
}

ProcessResult runIn(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& log,
                    double timeoutSeconds) {
    ProcessResult r;
    const pid_t pid = spawnIn(args, cwd, log);
    if (pid < 0) {
        r.output = "could not start " + args[0];
        return r;
    }
    r.exitCode = waitProcess(pid, timeoutSeconds);
    r.output = readFile(log);
    return r;
}

/// A fresh folder laid out as the repository root after scripts/run.sh: every top-level entry
/// of the source tree linked, build/bin the executables under test, no out/.
fs::path repositoryCopy(const fs::path& root) {
    fs::create_directories(root / "build");
    fs::create_directory_symlink(fs::absolute(binDir()), root / "build" / "bin");
    for (const auto& entry : fs::directory_iterator(sourceDir())) {
        const std::string name = entry.path().filename().string();
        if (name == ".git" || name == "out" || name == "cluster.secret" ||
            name.rfind("build", 0) == 0)
            continue;
        fs::create_symlink(fs::absolute(entry.path()), root / name);
    }
    return root;
}

std::string joined(const std::vector<std::string>& words) {
    std::string text;
    for (const auto& w : words) text += (text.empty() ? "" : " ") + w;
    return text;
}

/// An image a command wrote: readable, not empty, every pixel finite.
void expectImage(const std::string& where, const fs::path& path) {
    if (!fs::is_regular_file(path)) {
        ADD_FAILURE() << where << ": " << path << " was not written";
        return;
    }
    try {
        SCOPED_TRACE(where);
        const Image image = readFiniteImage(path);
        EXPECT_GT(image.width, 0) << where << ": " << path;
        EXPECT_GT(image.height, 0) << where << ": " << path;
        EXPECT_EQ(image.pixels.size(), std::size_t(image.width) * std::size_t(image.height))
            << where << ": " << path;
    } catch (const std::exception& e) {
        ADD_FAILURE() << where << ": " << path << " cannot be read: " << e.what();
    }
}

/// A master's outputs, as its command line names them, once it has exited.
struct MasterOutputs {
    std::vector<std::string> images;
    std::optional<std::string> sequence;
    std::optional<std::string> stats;
    int frames = 0;  ///< 0: until stopped

    explicit MasterOutputs(const std::vector<std::string>& words)
        : images(flagValues(words, "--output")),
          sequence(flagValue(words, "--output-sequence")),
          stats(flagValue(words, "--stats-json")),
          frames(intFlag(words, "--frames", kMasterDefaultFrames)) {}

    void expectWritten(const std::string& where, const fs::path& root) const {
        for (const auto& image : images) expectImage(where, root / image);
        if (sequence) {
            // Frames are numbered from 0; a stopped session wrote at least its first.
            for (int frame = 0; frame < std::max(frames, 1); ++frame) {
                char name[4096];
                std::snprintf(name, sizeof name, sequence->c_str(), frame);
                expectImage(where, root / name);
            }
        }
        if (stats) {
            if (!fs::is_regular_file(root / *stats)) {
                ADD_FAILURE() << where << ": " << *stats << " was not written";
                return;
            }
            try {
                std::ifstream file(root / *stats);
                const auto json = nlohmann::json::parse(file);
                EXPECT_FALSE(json.at("frames").empty()) << where << ": " << *stats;
                if (frames > 0) {
                    EXPECT_EQ(json.at("frames").size(), std::size_t(frames))
                        << where << ": " << *stats;
                }
            } catch (const std::exception& e) {
                ADD_FAILURE() << where << ": " << *stats << " is not the statistics: " << e.what();
            }
        }
    }
};

/// The state of one block while it runs: its ports, its background master and clients.
class BlockRun {
  public:
    BlockRun(const Block& block, fs::path root, fs::path logs)
        : block_(block), root_(std::move(root)), logs_(std::move(logs)) {}

    ~BlockRun() {
        // Whatever a failed block left running.
        std::vector<pid_t> all = clients_;
        if (master_) all.push_back(master_->pid);
        for (pid_t pid : all)
            if (pid > 0 && waitpid(pid, nullptr, WNOHANG) == 0)
                kill(pid, SIGKILL), waitpid(pid, nullptr, 0);
    }

    /// Runs every command of the block; `ran` and `skipped` list what it did.
    void run(std::vector<std::string>& ran, std::vector<std::string>& skipped) {
        for (const Command& command : block_.commands) {
            const Classified c = classify(command);
            if (c.kind == Kind::Skip) {
                skipped.push_back(command.where() + "  " + command.text +
                                  "\n      skipped: " + c.reason);
                continue;
            }
            if (c.kind == Kind::Unknown) {
                ADD_FAILURE() << command.where() << ": `" << command.text << "`: " << c.reason;
                continue;
            }
            const auto start = std::chrono::steady_clock::now();
            const std::string shown = runCommand(command, c);
            const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
            char seconds[32];
            std::snprintf(seconds, sizeof seconds, "  [%.1f s]", took.count());
            if (!shown.empty()) ran.push_back(command.where() + "  " + shown + seconds);
            if (::testing::Test::HasFatalFailure()) return;
        }
        const bool background = master_ || !clients_.empty();
        const auto start = std::chrono::steady_clock::now();
        finish();
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
        if (background) {
            char line[128];
            std::snprintf(line, sizeof line,
                          "  (end of the block: its background processes exited)  [%.1f s]",
                          took.count());
            ran.push_back(block_.file + ":" + std::to_string(block_.line) + line);
        }
    }

  private:
    /// 0.0.0.0, MASTER_HOST and localhost become 127.0.0.1; each fixed port a free one.
    std::string localize(const std::string& word) {
        static const std::regex address(R"((0\.0\.0\.0|127\.0\.0\.1|localhost|MASTER_HOST):(\d+))");
        std::string out;
        auto begin = word.cbegin();
        for (std::sregex_iterator it(word.begin(), word.end(), address), end; it != end; ++it) {
            out.append(begin, (*it)[0].first);
            std::string port = (*it)[2].str();
            if (port != "0") {
                auto& mapped = ports_[port];
                if (mapped.empty()) mapped = std::to_string(freePort());
                port = mapped;
            }
            out += "127.0.0.1:" + port;
            begin = (*it)[0].second;
        }
        out.append(begin, word.cend());
        return out;
    }

    std::vector<std::string> localize(std::vector<std::string> words) {
        for (auto& w : words) w = localize(w);
        return words;
    }

    fs::path log(const Command& command, const std::string& suffix = "") {
        std::string name = command.file + "-" + std::to_string(command.line) + suffix + ".log";
        std::replace(name.begin(), name.end(), '/', '_');
        return logs_ / name;
    }

    /// Runs one command; returns it as run (after the changes the file's comment lists).
    std::string runCommand(const Command& command, const Classified& c) {
        const std::string where = command.where();
        if (c.kind == Kind::Secret) {
            const ProcessResult r = runIn({"/bin/sh", "-c", command.text}, root_, log(command), 30);
            EXPECT_EQ(r.exitCode, 0) << where << ": `" << command.text << "`\n" << r.output;
            std::smatch m;
            std::regex_match(command.text, m, kSecretLine);
            EXPECT_GE(fs::exists(root_ / m[1].str()) ? fs::file_size(root_ / m[1].str()) : 0, 16u)
                << where << ": no secret in " << m[1].str();
            return command.text;
        }
        expectKnownFlags(where, command.text, command.words);
        std::vector<std::string> words = localize(command.words);
        if (c.kind == Kind::Master) return runMaster(command, std::move(words));
        if (c.kind == Kind::Client) return runClients(command, std::move(words));
        if (c.kind == Kind::Ctl) return runCtl(command, std::move(words));
        // Another tool: in the foreground, with fewer frames if it renders any.
        if (intFlag(words, "--frames", 0) > 0) setFlag(words, "--frames", std::to_string(kFrames));
        const ProcessResult r = runIn(words, root_, log(command), 120);
        EXPECT_EQ(r.exitCode, 0) << where << ": `" << joined(words) << "`\n" << r.output;
        return joined(words);
    }

    std::string runMaster(const Command& command, std::vector<std::string> words) {
        const std::string where = command.where();
        if (master_) {
            ADD_FAILURE() << where << ": a second master while " << master_->where << " still runs";
            return "";
        }
        // Without --frames the master renders its default, one frame: left as it is.
        if (intFlag(words, "--frames", 0) > 0) setFlag(words, "--frames", std::to_string(kFrames));
        if (!hasFlag(words, "--width") && !hasFlag(words, "--height")) {
            setFlag(words, "--width", kWidth);
            setFlag(words, "--height", kHeight);
        }
        const MasterOutputs outputs(words);
        const int remoteClients = intFlag(words, "--clients", 0);
        if (outputs.frames > 0 && remoteClients == 0) {
            const ProcessResult r = runIn(words, root_, log(command), 180);
            EXPECT_EQ(r.exitCode, 0) << where << ": `" << joined(words) << "`\n" << r.output;
            if (r.exitCode == 0) outputs.expectWritten(where, root_);
            return joined(words);
        }
        // In the background: it waits for remote clients, or renders until stopped.
        Background b{
            spawnIn(words, root_, log(command)), log(command), where, outputs, remoteClients,
            flagValue(words, "--control")};
        EXPECT_GT(b.pid, 0) << where << ": `" << joined(words) << "` did not start";
        master_ = b;
        return joined(words) + "   (in the background)";
    }

    std::string runClients(const Command& command, std::vector<std::string> words) {
        const std::string where = command.where();
        if (!master_ || master_->clients == 0) {
            ADD_FAILURE() << where << ": `" << command.text
                          << "` needs a master of the same block waiting for --clients";
            return "";
        }
        setFlag(words, "--threads", "1");
        const int copies = master_->clients - int(clients_.size());
        for (int i = 0; i < copies; ++i) {
            const pid_t pid =
                spawnIn(words, root_, log(command, "-client" + std::to_string(clients_.size())));
            EXPECT_GT(pid, 0) << where << ": `" << joined(words) << "` did not start";
            clients_.push_back(pid);
        }
        return joined(words) + "   (" + std::to_string(copies) + " copies, in the background)";
    }

    std::string runCtl(const Command& command, std::vector<std::string> words) {
        const std::string where = command.where();
        if (!master_ || !master_->control) {
            ADD_FAILURE() << where << ": `" << command.text
                          << "` needs a master of the same block with --control";
            return "";
        }
        if (!flagValue(words, "--connect"))
            words.insert(words.begin() + 1, {"--connect", *master_->control});
        const std::string connect = *flagValue(words, "--connect");
        if (!controlAnswered_) {
            // The master's control port opens after it has started: ask for its status until
            // it answers.
            const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
            ProcessResult r;
            while (std::chrono::steady_clock::now() < deadline) {
                r = runIn({words[0], "--connect", connect, "status"}, root_,
                          log(command, "-status"), 30);
                if (r.exitCode == 0 || waitpid(master_->pid, nullptr, WNOHANG) != 0) break;
                std::this_thread::sleep_for(std::chrono::milliseconds(100));
            }
            if (r.exitCode != 0) {
                ADD_FAILURE() << where << ": the master (" << master_->where
                              << ") never answered on " << connect << "\n"
                              << readFile(master_->log);
                return "";
            }
            controlAnswered_ = true;
        }
        const ProcessResult r = runIn(words, root_, log(command), 120);
        EXPECT_EQ(r.exitCode, 0) << where << ": `" << joined(words) << "`\n"
                                 << r.output << "\nmaster:\n"
                                 << readFile(master_->log);
        // The subcommand: the first word that is one of igi-ctl's.
        std::size_t sub = 1;
        while (sub < words.size() && !help().subcommands("igi-ctl").count(words[sub])) ++sub;
        const std::string name = sub < words.size() ? words[sub] : "";
        if (name == "snapshot" && r.exitCode == 0 && sub + 1 < words.size())
            expectImage(where, root_ / words[sub + 1]);
        if (name == "stop") waitForMaster(where);
        return joined(words);
    }

    /// The background master exits by itself (it rendered its frames) or after `stop`: with
    /// code 0, having written its outputs.
    void waitForMaster(const std::string& where) {
        if (!master_) return;
        const int code = waitProcess(master_->pid, 180);
        EXPECT_EQ(code, 0) << where << ": the master of " << master_->where << " exited with "
                           << code << "\n"
                           << readFile(master_->log);
        if (code == 0) master_->outputs.expectWritten(master_->where, root_);
        master_->pid = -1;
        finishedMaster_ = master_->where;
        master_.reset();
    }

    void finish() {
        if (master_) {
            if (master_->outputs.frames == 0) {
                ADD_FAILURE() << master_->where
                              << ": a master that renders until stopped (--frames 0), but its "
                                 "block has no `igi-ctl ... stop`";
                return;
            }
            if (int(clients_.size()) < master_->clients)
                ADD_FAILURE() << master_->where << ": waits for " << master_->clients
                              << " clients, but its block starts " << clients_.size();
            waitForMaster(master_->where + " (end of block)");
        }
        for (std::size_t i = 0; i < clients_.size(); ++i) {
            const int code = waitProcess(clients_[i], 60);
            EXPECT_EQ(code, 0) << "client " << i << " of " << finishedMaster_ << " exited with "
                               << code;
            clients_[i] = -1;
        }
    }

    struct Background {
        pid_t pid = -1;
        fs::path log;
        std::string where;
        MasterOutputs outputs;
        int clients = 0;
        std::optional<std::string> control;
    };

    const Block& block_;
    fs::path root_, logs_;
    std::map<std::string, std::string> ports_;
    std::optional<Background> master_;
    std::string finishedMaster_;
    std::vector<pid_t> clients_;
    bool controlAnswered_ = false;
};

// ---------------------------------------------------------------------------------------------

std::vector<Block> allBlocks() {
    std::vector<Block> blocks;
    for (const auto& doc : documents())
        for (auto& block : commandBlocks(doc)) blocks.push_back(std::move(block));
    return blocks;
}

TEST(DocCommands, EveryCommandIsRunOrSkippedForAStatedReason) {
    std::map<Kind, int> counts;
    for (const Block& block : allBlocks())
        for (const Command& command : block.commands) {
            const Classified c = classify(command);
            ++counts[c.kind];
            if (c.kind == Kind::Unknown)
                ADD_FAILURE() << command.where() << ": `" << command.text << "`: " << c.reason
                              << ". Make it one that runs as written from the repository root, "
                                 "or add it to the skip list of tests/DocCommands_test.cpp with "
                                 "the reason it cannot run here.";
        }
    // The documents' own examples are found: the parser has not gone blind.
    EXPECT_GE(counts[Kind::Master], 3) << "igi-master commands found in the documents";
    EXPECT_GE(counts[Kind::Client], 1) << "igi-client commands found in the documents";
    EXPECT_GE(counts[Kind::Ctl], 3) << "igi-ctl commands found in the documents";
    EXPECT_GE(counts[Kind::Skip], 2) << "skipped commands found in the documents";
}

TEST(DocCommands, SingleMachineExamplesRunAsWritten) {
    const fs::path dir = scratchDir("doc-commands");
    std::vector<std::string> ran, skipped;
    int index = 0;
    for (const Block& block : allBlocks()) {
        SCOPED_TRACE(block.file + ":" + std::to_string(block.line) + ": code block");
        const fs::path root = dir / ("root" + std::to_string(index));
        const fs::path logs = dir / ("logs" + std::to_string(index));
        ++index;
        fs::create_directories(logs);
        repositoryCopy(root);
        BlockRun(block, root, logs).run(ran, skipped);
        if (HasFatalFailure()) break;
    }
    std::cout << "Ran, from a copy of the repository root's layout:\n";
    for (const auto& line : ran) std::cout << "  " << line << "\n";
    std::cout << "Skipped:\n";
    for (const auto& line : skipped) std::cout << "  " << line << "\n";
    EXPECT_FALSE(ran.empty());
    if (!HasFailure())
        fs::remove_all(dir);
    else
        std::cout << "Scratch folders and logs kept in " << dir << "\n";
}

TEST(DocCommands, ProseNamesOnlyExistingFlagsAndScripts) {
    static const std::regex command(
        R"(^(build/bin/)?(igi-master|igi-client|igi-ctl|igi-compare|igi-bench|igi-codec-bench)( |$))");
    static const std::regex script(R"(^([A-Z_]+=\S+ )*scripts/[^ ]+\.(sh|py)( |$))");
    static const std::regex bareFlags(R"(^--[A-Za-z0-9][A-Za-z0-9-]*( .*)?$)");
    // Flags of other programs that the documents mention: Embree's pathtracer (docs/ACCURACY.md).
    static const std::set<std::string> foreign = {"--vp", "--vi", "--vu", "--fov"};
    std::set<std::string> everyFlag(foreign.begin(), foreign.end());
    for (const auto& binary : kBinaries) {
        const auto& f = help().flags(binary);
        everyFlag.insert(f.begin(), f.end());
        for (const auto& sub : help().subcommands(binary)) {
            const auto& s = help().flags(binary, sub);
            everyFlag.insert(s.begin(), s.end());
        }
    }
    for (const auto& entry : fs::directory_iterator(sourceDir() / "scripts")) {
        static const std::regex flag(R"(--[A-Za-z0-9][A-Za-z0-9-]*)");
        const std::string text = readFile(entry.path());
        for (std::sregex_iterator it(text.begin(), text.end(), flag), end; it != end; ++it)
            everyFlag.insert(it->str());
    }

    int commands = 0;
    for (const auto& doc : documents()) {
        for (const Span& span : inlineSpans(doc)) {
            const std::string where = span.file + ":" + std::to_string(span.line);
            const auto words = shellWords(span.text).words;
            if (std::regex_search(span.text, command)) {
                ++commands;
                expectKnownFlags(where, span.text, words);
            } else if (std::regex_search(span.text, script)) {
                expectScriptFlags(where, span.text, words);
            } else if (std::regex_match(span.text, bareFlags)) {
                // A flag alone (`--reconnect-seconds`): some executable or script has it.
                for (const auto& flag : namedFlags(words))
                    EXPECT_TRUE(everyFlag.count(flag))
                        << where << ": `" << span.text << "` names " << flag
                        << ", which no executable's --help lists and no script handles";
            }
        }
        // The code blocks' commands too, the skipped ones included: no stale flag, no missing
        // script.
        for (const Block& block : commandBlocks(doc))
            for (const Command& c : block.commands) {
                const Kind kind = classify(c).kind;
                const std::size_t s = commandStart(c.words);
                if (s < c.words.size() && c.words[s].rfind("scripts/", 0) == 0)
                    expectScriptFlags(c.where(), c.text, c.words);
                else if (kind == Kind::Master || kind == Kind::Client || kind == Kind::Ctl ||
                         kind == Kind::Tool)
                    expectKnownFlags(c.where(), c.text, c.words);
            }
    }
    EXPECT_GE(commands, 10) << "inline commands found in the documents";
}

// docs/PERFORMANCE.md is written whole by scripts/perf_report.py, but some of its blocks come from
// other scripts (shadow_rays_report.py, bench_view.sh, ...) or by hand: the report copies each from
// the document it replaces. A block it does not copy is lost at the next regeneration, as the
// shadow-rays block once was; the report refuses to write then, and this test says so sooner.
TEST(DocCommands, PerformanceReportKeepsEveryBlockOfTheDocument) {
    const std::string doc = readFile(sourceDir() / "docs" / "PERFORMANCE.md");
    const std::string report = readFile(sourceDir() / "scripts" / "perf_report.py");
    static const std::regex block(R"(<!-- BEGIN GENERATED ([^ ]+) -->)");
    int blocks = 0;
    for (std::sregex_iterator it(doc.begin(), doc.end(), block), end; it != end; ++it) {
        ++blocks;
        const std::string key = (*it)[1].str();
        EXPECT_NE(report.find("generated_block(doc, \"" + key + "\")"), std::string::npos)
            << "docs/PERFORMANCE.md has the block '" << key
            << "', which scripts/perf_report.py does not keep";
    }
    EXPECT_GE(blocks, 6);
}

}  // namespace
}  // namespace igi
