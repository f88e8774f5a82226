# bash completion for the vmass tools, from their own --help (so it never falls behind them).
# Installed once per tool name in /usr/share/bash-completion/completions.
_vmass_complete() {
  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD - 1]} tool=${COMP_WORDS[0]}
  local help sub="" word
  if [[ $tool == vmass-can && $COMP_CWORD -ge 2 ]]; then
    sub=${COMP_WORDS[1]}
  fi
  if [[ $tool == vmass-ctl ]]; then  # its subcommand may follow the global options
    for word in "${COMP_WORDS[@]:1:COMP_CWORD-1}"; do
      [[ $word == known-mass || $word == reset-learnt ]] && sub=$word
    done
  fi
  help=$("$tool" ${sub:+"$sub"} --help 2>/dev/null)
  if [[ $tool == vmass-can && $COMP_CWORD -eq 1 ]]; then
    mapfile -t COMPREPLY < <(compgen -W "check decode dump --help --version" -- "$cur")
    return
  fi
  if [[ $tool == vmass-ctl && -z $sub && $cur != -* && $prev != --* ]]; then
    mapfile -t COMPREPLY < <(compgen -W "known-mass reset-learnt" -- "$cur")
    return
  fi
  case $prev in
    --config | --dbc | --log | --samples | --truth | --replay | --ballast | --out | --plot | \
      --write-config | --state-file | --estimates | --csv-dir)
      mapfile -t COMPREPLY < <(compgen -f -- "$cur")
      compopt -o filenames 2>/dev/null
      return ;;
    --estimator)
      mapfile -t COMPREPLY < <(compgen -W "rls bayes" -- "$cur")
      return ;;
    --can)
      mapfile -t COMPREPLY < <(compgen -W "$(ls /sys/class/net 2>/dev/null)" -- "$cur")
      return ;;
    --interface)  # of a log: ASC, TRC, BLF channel and MDF4 bus N are can<N-1>
      mapfile -t COMPREPLY < <(compgen -W "can0 can1 can2 can3" -- "$cur")
      return ;;
  esac
  if [[ $cur == -* ]]; then
    mapfile -t COMPREPLY < <(compgen -W "$(grep -oE -- '--[a-z][a-z0-9-]*' <<<"$help" | sort -u)" \
      -- "$cur")
  else
    mapfile -t COMPREPLY < <(compgen -f -- "$cur")
    compopt -o filenames 2>/dev/null
  fi
}
complete -F _vmass_complete vmassd vmass-replay vmass-calibrate vmass-sim vmass-can \
  vmass-monitor vmass-ctl vmass-plot vmass-lcmlog-csv vmass-log-convert vmass-spy vmass-numerics
