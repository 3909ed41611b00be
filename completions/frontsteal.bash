# bash completion for frontsteal: subcommands, then the options of the chosen subcommand, both read from the
# command's own --help (so they cannot drift from it). Load with:  . completions/frontsteal.bash
_frontsteal() {
  local cur=${COMP_WORDS[COMP_CWORD]} sub= i
  for ((i = 1; i < COMP_CWORD; i++)); do
    case ${COMP_WORDS[i]} in -*) ;; *) sub=${COMP_WORDS[i]}; break ;; esac
  done
  if [[ -z $sub && $cur != -* ]]; then
    local subs
    subs=$(frontsteal --help 2>/dev/null | sed -n '/subcommands (/,/^$/p' | awk 'NR > 1 && NF { print $1 }')
    COMPREPLY=($(compgen -W "$subs" -- "$cur"))
  elif [[ $cur == -* ]]; then
    local opts
    opts=$(frontsteal ${sub:+"$sub"} --help 2>/dev/null | grep -o -- '--[a-z][a-z0-9-]*' | sort -u)
    COMPREPLY=($(compgen -W "$opts" -- "$cur"))
  fi
}
complete -o default -F _frontsteal frontsteal
