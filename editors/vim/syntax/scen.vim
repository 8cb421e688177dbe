" Vim syntax file
" Language:   scen (scenarios for 2D robot motion planning, SPEC.md §2)
" Filenames:  *.scen
"
" The same colouring classes as the VS Code grammar
" (editors/vscode/syntaxes/scen.tmLanguage.json). tests/editors.rs checks
" that every keyword, planner kind, parameter key, word value and metric
" that `scen` accepts is listed here.

if exists('b:current_syntax')
  finish
endif
let s:cpo_save = &cpo
set cpo&vim

syn case match
syn iskeyword @,48-57,_

" ------------------------------------------------ stray text, punctuation
" Defined first: every later item that starts at the same place wins.
syn match   scenStray /\S/
syn match   scenPunct /[()[\],]/
syn match   scenOtherWord /\<\h\w*/

" ------------------------------------------------------------- comments
syn keyword scenTodo contained TODO FIXME XXX NOTE
syn match   scenComment /#.*$/ contains=scenTodo,@Spell

" -------------------------------------------------------------- strings
" A string ends at the end of its line; `\"` and `\\` are its escapes.
syn match   scenUnterminated /"\%([^"\\]\|\\.\)*\\\=$/
syn region  scenString start=/"/ skip=/\\./ end=/"/ oneline contains=scenEscape,scenBadEscape
syn match   scenBadEscape contained /\\./
syn match   scenEscape contained /\\["\\]/

" -------------------------------------------------------------- numbers
" `12`, `-3.5`, `1e-3`, `.5`, and with a unit: `90deg`, `1.5rad`, `100%`,
" `500ms`, `2s`. Anything else glued to a number is a malformed number
" (`1.2.3`, `90degx`, `5-3`).
syn match   scenBadNumber /\%([[:alnum:]_.]\)\@1<!-\=\.\=\d[[:alnum:]_.%+-]*/
syn match   scenNumber    /\%([[:alnum:]_.]\)\@1<!-\=\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%([[:alnum:]_.%+-]\)\@!/
syn match   scenAngle     /\%([[:alnum:]_.]\)\@1<!-\=\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%(deg\|rad\)\%([[:alnum:]_.%+-]\)\@!/ contains=scenUnit
syn match   scenPercent   /\%([[:alnum:]_.]\)\@1<!-\=\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=%\%([[:alnum:]_.%+-]\)\@!/ contains=scenUnit
syn match   scenDuration  /\%([[:alnum:]_.]\)\@1<!-\=\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%(ms\|s\)\%([[:alnum:]_.%+-]\)\@!/ contains=scenUnit
syn match   scenUnit contained /\%(deg\|rad\|ms\|s\|%\)\%([[:alnum:]_]\)\@!/
syn cluster scenNumbers contains=scenBadNumber,scenNumber,scenAngle,scenPercent,scenDuration
" In `expect`, `-` is an operator (`2-1`) and a duration is an error:
" metrics are plain numbers.
syn match   scenExprBadNumber contained /\%([[:alnum:]_.]\)\@1<!\.\=\d\%([eE][-+]\=\|[[:alnum:]_.%]\)*/
syn match   scenExprNumber contained    /\%([[:alnum:]_.]\)\@1<!\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%([[:alnum:]_.%]\)\@!/
syn match   scenExprAngle contained     /\%([[:alnum:]_.]\)\@1<!\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%(deg\|rad\)\%([[:alnum:]_.%]\)\@!/ contains=scenUnit
syn match   scenExprPercent contained   /\%([[:alnum:]_.]\)\@1<!\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=%\%([[:alnum:]_.%]\)\@!/ contains=scenUnit
syn match   scenExprDuration contained /\%([[:alnum:]_.]\)\@1<!\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%(ms\|s\)\%([[:alnum:]_.%]\)\@!/
syn cluster scenExprNumbers contains=scenExprBadNumber,scenExprNumber,scenExprAngle,scenExprPercent,scenExprDuration

" ----------------------------------------------------------- statements
" A statement keyword followed by `.` is a plan name (`plan.found`).
syn match   scenStatement /\<\%(scenario\|include\|world\)\>\%(\s*\.\)\@!/
syn match   scenStatement /\<robot\>\%(\s*\.\)\@!/ nextgroup=scenName skipwhite
syn match   scenStatement /\<plan\>\%(\s*\.\)\@!/ nextgroup=scenPlanName skipwhite

" robot NAME SHAPE
syn match   scenName contained /\h\w*/ nextgroup=scenShape skipwhite
" plan NAME KIND ROBOT
syn match   scenPlanName contained /\h\w*/ nextgroup=scenPlanner,scenBadPlanner skipwhite
syn match   scenBadPlanner contained /\h\w*/ nextgroup=scenRobotRef skipwhite
syn keyword scenPlanner contained astar online roadmap potential coverage nextgroup=scenRobotRef skipwhite
syn match   scenRobotRef contained /\h\w*/

" Obstacles and robot shapes; an obstacle's name follows its kind
" (`grid cell 1` has none: `cell` is then the grid's option).
syn keyword scenShape rect polygon segment disk grid point nextgroup=scenObstacleName skipwhite
syn match   scenObstacleName contained /\%(\%(cell\|origin\)\s*[-.0-9(\["]\)\@!\h\w*/

" ------------------------------------------------- world and plan blocks
syn region  scenBlock matchgroup=scenBrace start=/{/ end=/}/ fold
      \ contains=scenStray,scenPunct,scenOtherWord,scenBlock,scenComment,scenString,scenUnterminated,@scenNumbers,scenShape,scenWorldKeyword,scenParamKey,scenLimitKind,scenWord
syn keyword scenWorldKeyword contained bounds origin
" Parameter keys: the common ones, every planner's, and `drive { ... }`'s.
syn keyword scenParamKey contained start goal limit seed drive
syn keyword scenParamKey contained cell sample connect layers cost turn_cost weight heuristic rotate
syn keyword scenParamKey contained strategy sense
syn keyword scenParamKey contained arc_segments
syn keyword scenParamKey contained attract repulse influence step tolerance escape jump
syn keyword scenParamKey contained on tool weights
syn keyword scenParamKey contained dt max_speed max_turn_rate gain turn_gain reach align
" `limit expansions N | steps N | time DURATION | cells N | iterations N`
syn keyword scenLimitKind contained expansions steps time cells iterations
" Word values.
syn keyword scenWord contained center corner auto euclid l1 lattice metric zero yes no
syn keyword scenWord contained backtrack shortcut replan dstar_lite none random_walk max sum
syn keyword scenWord contained unicycle

" --------------------------------------------------------------- expect
" An expression runs until the next statement.
syn region  scenExpect matchgroup=scenStatement start=/\<expect\>\%(\s*\.\)\@!/
      \ end=/\ze\<\%(scenario\|include\|world\|robot\|plan\|expect\)\>\%(\s*\.\)\@!/
      \ contains=scenStray,scenBareWord,scenParen,scenAccessor,scenComment,scenPlanRef,scenOtherMetric,scenMetric,scenOperator,scenLogical,scenBoolean,@scenExprNumbers
" A bare word is not an operand: write `PLAN.METRIC`.
syn match   scenBareWord contained /\<\h\w*/
syn match   scenParen contained /[()]/
syn match   scenAccessor contained /\.\ze\h/
syn match   scenPlanRef contained /\<\h\w*\ze\.\h/
syn match   scenOtherMetric contained /\.\@1<=\h\w*/
syn match   scenMetric contained /\.\@1<=\%(found\|gave_up\|cost\|length\|turn\|nodes\|expanded\|time_ms\|collision_free\|reaches_goal\)\>/
syn match   scenMetric contained /\.\@1<=\%(cells\|free_cells\|layers\|generated\)\>/
syn match   scenMetric contained /\.\@1<=\%(traveled\|steps\|replans\|sensed\)\>/
syn match   scenMetric contained /\.\@1<=\%(graph_nodes\|graph_edges\)\>/
syn match   scenMetric contained /\.\@1<=\%(minima\|escapes\)\>/
syn match   scenMetric contained /\.\@1<=\%(coverage\|cells_total\|cells_visited\|revisits\|returns_to_start\|uncovered\|tree_edges\|tree_weight\)\>/
syn match   scenMetric contained /\.\@1<=\%(drive_time\|drive_max_deviation\|drive_collision_free\)\>/
syn match   scenOperator contained /<=\|>=\|==\|!=\|<\|>\|\~\|+-\|±\|[-+*\/]/
syn keyword scenLogical contained and or not
syn keyword scenBoolean contained true false
syn sync minlines=200

" ---------------------------------------------------------------- links
hi def link scenTodo          Todo
hi def link scenComment       Comment
hi def link scenString        String
hi def link scenEscape        SpecialChar
hi def link scenBadEscape     Error
hi def link scenUnterminated  Error
hi def link scenNumber        Number
hi def link scenAngle         Number
hi def link scenPercent       Number
hi def link scenDuration      Number
hi def link scenUnit          Special
hi def link scenBadNumber     Error
hi def link scenExprNumber    Number
hi def link scenExprAngle     Number
hi def link scenExprPercent   Number
hi def link scenExprBadNumber Error
hi def link scenExprDuration  Error
hi def link scenStray         Error
hi def link scenBareWord      Error
hi def link scenStatement     Statement
hi def link scenShape         Type
hi def link scenWorldKeyword  Keyword
hi def link scenName          Function
hi def link scenPlanName      Function
hi def link scenObstacleName  Function
hi def link scenPlanner       Structure
hi def link scenBadPlanner    Error
hi def link scenParamKey      Identifier
hi def link scenLimitKind     Identifier
hi def link scenWord          Constant
hi def link scenMetric        PreProc
hi def link scenOperator      Operator
hi def link scenLogical       Operator
hi def link scenBoolean       Boolean
hi def link scenBrace         Delimiter

let b:current_syntax = 'scen'
let &cpo = s:cpo_save
unlet s:cpo_save
