// SPDX-License-Identifier: MIT
#include "skyservice/app/toml_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace sky
{
namespace
{

struct TextPosition
{
    size_t line = 1, column = 1;
};

/// The first byte >= 0x80 outside a string or a comment, if any. TOML keys, numbers, booleans and dates are
/// ASCII, so such a byte is an error wherever it is found; it is refused here because toml++ 3.3 (Debian 12)
/// reaches an unreachable branch (undefined behaviour) classifying some code points there, e.g. U+FDFF
/// where a key begins (found by the config fuzzer).
bool findNonAsciiOutsideStrings(const std::string& text, TextPosition& where)
{
    enum class State { Normal, Comment, Basic, Literal, MultiBasic, MultiLiteral };
    State state = State::Normal;
    TextPosition at;
    for (size_t i = 0; i < text.size(); ++i)
    {
        const char c = text[i];
        const auto startsWith = [&](const char* s) {
            return text.compare(i, std::char_traits<char>::length(s), s) == 0;
        };
        switch (state)
        {
        case State::Normal:
            if ((static_cast<unsigned char>(c) & 0x80u) != 0)
            {
                where = at;
                return true;
            }
            if (c == '#')
                state = State::Comment;
            else if (startsWith("\"\"\""))
                state = State::MultiBasic, i += 2, at.column += 2;
            else if (startsWith("'''"))
                state = State::MultiLiteral, i += 2, at.column += 2;
            else if (c == '"')
                state = State::Basic;
            else if (c == '\'')
                state = State::Literal;
            break;
        case State::Comment:
            if (c == '\n')
                state = State::Normal;
            break;
        case State::Basic:
        case State::MultiBasic:
            if (c == '\\' && i + 1 < text.size() && text[i + 1] != '\n')
                ++i, ++at.column;  // an escaped character (a quote does not end the string)
            else if (state == State::Basic && (c == '"' || c == '\n'))
                state = State::Normal;  // a newline ends it too: toml++ reports that
            else if (state == State::MultiBasic && startsWith("\"\"\""))
                state = State::Normal, i += 2, at.column += 2;
            break;
        case State::Literal:
            if (c == '\'' || c == '\n')
                state = State::Normal;
            break;
        case State::MultiLiteral:
            if (startsWith("'''"))
                state = State::Normal, i += 2, at.column += 2;
            break;
        }
        if (c == '\n')
            ++at.line, at.column = 1;
        else
            ++at.column;
    }
    return false;
}

}  // namespace

bool parseTomlFile(const std::string& path, toml::table& out, std::string& error)
{
    std::error_code code;
    if (!std::filesystem::is_regular_file(path, code))
    {
        error = path + (code ? ": " + code.message() : std::string(": not a regular file"));
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        error = path + ": cannot be opened";
        return false;
    }
    std::ostringstream text;
    text << in.rdbuf();
    const std::string content = text.str();
    TextPosition where;
    if (findNonAsciiOutsideStrings(content, where))
    {
        error = path + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                ": a non-ASCII character outside a string or comment (keys and values other than strings are ASCII)";
        return false;
    }
    try
    {
        out = toml::parse(content, path);
        return true;
    }
    catch (const toml::parse_error& e)
    {
        const auto& begin = e.source().begin;
        error = path + ":" + std::to_string(begin.line) + ":" + std::to_string(begin.column) + ": " +
                std::string(e.description());
        return false;
    }
}

}  // namespace sky
