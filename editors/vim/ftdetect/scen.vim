" .scen files: scenarios for the `scen` robot motion planning interpreter.
autocmd BufRead,BufNewFile *.scen setfiletype scen
