" Reads `scen check --format json` output (the file g:json) with the
" errorformat of editors/vim/ftplugin/scen.vim and writes the quickfix
" entries to g:out, one per line: FILE|LINE|COLUMN|TYPE|TEXT|VALID.
let &runtimepath = expand('<sfile>:p:h:h') . '/vim,' . &runtimepath
filetype plugin on
enew
setfiletype scen
execute 'cgetfile ' . fnameescape(g:json)
let s:out = []
for s:e in getqflist()
  call add(s:out, join([bufname(s:e.bufnr), s:e.lnum, s:e.col, s:e.type, s:e.text, s:e.valid], '|'))
endfor
call writefile(s:out, g:out)
qall!
