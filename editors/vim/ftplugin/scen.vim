" Comments run from `#` to the end of the line (for `gc` in Neovim and
" commentary.vim, and for `gq` formatting of comments).
if exists('b:did_ftplugin')
  finish
endif
let b:did_ftplugin = 1

setlocal commentstring=#\ %s
setlocal comments=:#
setlocal formatoptions-=t formatoptions+=croql
setlocal iskeyword=@,48-57,_
" `:make` checks the file with `scen check --format json` (one JSON object
" per diagnostic) and fills the quickfix list.
setlocal makeprg=scen\ check\ --format\ json\ %:S
let &l:errorformat = '{"severity":"%t%.%#"\,"code":%.%#"message":"%m"\,"label"%.%#"file":"%f"\,"line":%l\,"column":%c\,%.%#'
let b:undo_ftplugin = 'setlocal commentstring< comments< formatoptions< iskeyword< makeprg< errorformat<'
