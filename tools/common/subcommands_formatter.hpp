// --help-all as help2man reads it for a man page: each subcommand's options under a heading of
// its own ("check (validate a DBC file...):", a subsection), laid out as --help lays out
// options. The tools with subcommands (vmass-can, vmass-ctl) install it with app.formatter().
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace vmass::tools {

class SubcommandsFormatter : public CLI::Formatter {
 public:
  std::string make_expanded(const CLI::App* sub) const override {
    std::string out = "\n" + sub->get_name() + " (" + sub->get_description() + "):\n";
    for (const CLI::Option* opt : sub->get_options()) {
      if (opt == sub->get_help_ptr() || opt == sub->get_help_all_ptr()) continue;
      out += make_option(opt, opt->get_positional());
    }
    return out;
  }
};

}  // namespace vmass::tools
