# bash completion for lcm_control's programs: their flags and subcommands, read
# from the program's own --help, so completion follows the program's version.
_lcm_control() {
  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} help words
  case $prev in
    --urdf | --config | -o | --output | --output-dir | --log | --file | --csv | --data | --package-path)
      COMPREPLY=($(compgen -f -- "$cur"))
      return
      ;;
  esac
  help=$("${COMP_WORDS[0]}" --help 2>/dev/null) || return
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
complete -F _lcm_control sim_server controller_manager launch spawner cmctl turret-cmd send-trajectory gripper \
  state-logger state-publisher log2csv plotter tune doctor tracking-summary bus drive
