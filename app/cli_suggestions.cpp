#include "app/cli_suggestions.h"

#include <vector>

#include "scene_io/did_you_mean.h"

namespace invfree {

namespace {

std::vector<std::string> long_options(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options())
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
  return names;
}

}  // namespace

std::string cli_suggestions(CLI::App& app) {
  std::vector<CLI::App*> selected = app.get_subcommands();
  CLI::App* command = selected.empty() ? nullptr : selected.front();
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    commands.push_back(sub->get_name());
  std::vector<std::string> options = long_options(app);
  if (command) {
    const std::vector<std::string> own = long_options(*command);
    options.insert(options.end(), own.begin(), own.end());
  }
  std::string out;
  for (const std::string& word : app.remaining(true)) {
    std::string nearest;
    if (word.starts_with("--"))
      nearest = nearest_word(word.substr(0, word.find('=')), options);
    else if (!command && !word.starts_with("-"))
      nearest = nearest_word(word, commands);
    if (!nearest.empty())
      out += (out.empty() ? "" : ", ") + ("\"" + nearest + "\" for \"" + word + "\"");
  }
  if (!out.empty()) return " (did you mean " + out + "?)";
  if (!command && !app.remaining(true).empty() && !app.remaining(true).front().starts_with("-"))
    return " (commands: " + join_words(commands) + ")";
  return "";
}

}  // namespace invfree
