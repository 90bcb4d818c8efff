# bash completion for lcm-control, the installed command: the program's name (from `lcm-control --help`), then that
# program's flags and subcommands, read from its own --help, so completion follows the programs' version.
_lcm_control() {
  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} help words
  local -a command=("${COMP_WORDS[0]}")
  ((COMP_CWORD > 1)) && command+=("${COMP_WORDS[1]}")
  case $prev in
    --urdf | --config | -o | --output | --output-dir | --log | --file | --csv | --data | --package-path)
      COMPREPLY=($(compgen -f -- "$cur"))
      return
      ;;
  esac
  help=$("${command[@]}" --help 2>/dev/null) || return
  if [[ $cur == -* ]]; then
    words=$(grep -oE -- '--[a-zA-Z0-9][a-zA-Z0-9-]*' <<<"$help" | sort -u)
  else
    # "  name, alias, ...   description": every name and alias
    words=$(awk '/^Subcommands:/ { s = 1; next }
                 s && /^  [a-z]/ { for (i = 1; i <= NF; i++) { n = $i; a = sub(/,$/, "", n); print n; if (!a) break } }' <<<"$help")
  fi
  if [[ -z $words ]]; then
    COMPREPLY=($(compgen -f -- "$cur"))
  else
    COMPREPLY=($(compgen -W "$words" -- "$cur"))
  fi
}
complete -F _lcm_control lcm-control
